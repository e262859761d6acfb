#!/usr/bin/env node
// Loads a slipload HTML report in headless chromium and checks it:
//   - no console errors, no page errors, no failed requests;
//   - no request leaves the file (anything but file:// and data: is blocked and reported:
//     the report must open offline);
//   - every top-level inline <svg> has a non-zero rendered width and height;
//   - at least --min-tables tables and --min-svgs inline SVGs exist, and every table has rows.
// Writes a full-page screenshot to OUT.png and prints a JSON summary on stdout.
// Exit status: 0 when every check passes, 1 when one fails, 2 on a usage or launch error.
//
// Usage: node check-report.mjs FILE.html OUT.png [--min-tables N] [--min-svgs N]
// Chromium: $CHROMIUM or /usr/bin/chromium (Debian: apt-get install -y chromium).

import { chromium } from 'playwright-core';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { pathToFileURL } from 'node:url';

function usage(msg) {
  console.error(`check-report: ${msg}`);
  console.error('usage: node check-report.mjs FILE.html OUT.png [--min-tables N] [--min-svgs N]');
  process.exit(2);
}

const argv = process.argv.slice(2);
const positional = [];
const opts = { minTables: 1, minSvgs: 0 };
for (let i = 0; i < argv.length; i++) {
  const a = argv[i];
  if (a === '--min-tables' || a === '--min-svgs') {
    const v = Number.parseInt(argv[++i], 10);
    if (!Number.isFinite(v) || v < 0) usage(`${a} needs a count`);
    opts[a === '--min-tables' ? 'minTables' : 'minSvgs'] = v;
  } else if (a.startsWith('--')) {
    usage(`unknown option ${a}`);
  } else {
    positional.push(a);
  }
}
if (positional.length !== 2) usage('give the report file and the screenshot file');
const [htmlFile, pngFile] = positional;
if (!fs.existsSync(htmlFile)) usage(`${htmlFile} does not exist`);

const executablePath = process.env.CHROMIUM || '/usr/bin/chromium';
if (!fs.existsSync(executablePath)) {
  usage(`chromium not found at ${executablePath}: install it (Debian: apt-get install -y chromium) or set CHROMIUM`);
}

const userDataDir = fs.mkdtempSync(path.join(os.tmpdir(), 'slipload-check-report-'));
const problems = [];
const consoleErrors = [];
const pageErrors = [];
const blocked = [];
const failed = [];
let context;
let summary;
try {
  context = await chromium.launchPersistentContext(userDataDir, {
    executablePath,
    headless: true,
    args: [
      '--headless', '--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run',
      '--disable-background-networking', '--disable-component-update', '--disable-sync',
    ],
    viewport: { width: 1280, height: 900 },
    timeout: 60_000,
  });
  const page = context.pages()[0] ?? (await context.newPage());
  await page.route('**/*', (route) => {
    const url = route.request().url();
    if (url.startsWith('file:') || url.startsWith('data:')) return route.continue();
    blocked.push(url);
    return route.abort();
  });
  page.on('console', (msg) => {
    if (msg.type() === 'error') consoleErrors.push(msg.text());
  });
  page.on('pageerror', (err) => pageErrors.push(String(err)));
  page.on('requestfailed', (req) => {
    if (!blocked.includes(req.url())) failed.push(`${req.url()}: ${req.failure()?.errorText}`);
  });

  const url = pathToFileURL(path.resolve(htmlFile)).href;
  const response = await page.goto(url, { waitUntil: 'load', timeout: 60_000 });
  if (response && !response.ok()) problems.push(`loading ${url}: status ${response.status()}`);

  const facts = await page.evaluate(() => {
    // SVGs inside a closed <details> have no layout: open their ancestors first.
    const svgs = [...document.querySelectorAll('svg')].filter((s) => !s.parentElement.closest('svg'));
    for (const s of svgs) {
      for (let d = s.closest('details'); d; d = d.parentElement.closest('details')) d.open = true;
    }
    const sized = svgs.map((s) => {
      const r = s.getBoundingClientRect();
      const fig = s.closest('figure');
      return { id: fig ? fig.id : '', width: r.width, height: r.height };
    });
    const tables = [...document.querySelectorAll('table')].map((t) => t.rows.length);
    return {
      title: document.title,
      h1: document.querySelector('h1')?.textContent ?? '',
      svgs: sized,
      tables,
      bodyHeight: document.body.scrollHeight,
    };
  });

  for (const s of facts.svgs) {
    if (!(s.width > 0 && s.height > 0)) problems.push(`inline svg ${s.id || '(no figure id)'} has size ${s.width} x ${s.height}`);
  }
  if (facts.svgs.length < opts.minSvgs) problems.push(`${facts.svgs.length} inline svg(s), expected at least ${opts.minSvgs}`);
  if (facts.tables.length < opts.minTables) problems.push(`${facts.tables.length} table(s), expected at least ${opts.minTables}`);
  facts.tables.forEach((rows, i) => {
    if (rows < 1) problems.push(`table ${i + 1} has no rows`);
  });
  if (!facts.h1) problems.push('the page has no <h1> title');

  await page.screenshot({ path: pngFile, fullPage: true });
  summary = {
    file: htmlFile,
    screenshot: pngFile,
    title: facts.title,
    svgs: facts.svgs,
    tables: facts.tables.length,
    pageHeight: facts.bodyHeight,
    consoleErrors,
    pageErrors,
    blockedRequests: blocked,
    failedRequests: failed,
  };
} catch (err) {
  console.error(`check-report: ${err?.stack ?? err}`);
  process.exitCode = 2;
} finally {
  if (context) await context.close();
  fs.rmSync(userDataDir, { recursive: true, force: true });
}

if (summary) {
  for (const e of consoleErrors) problems.push(`console error: ${e}`);
  for (const e of pageErrors) problems.push(`page error: ${e}`);
  for (const u of blocked) problems.push(`external request blocked (the report must be self-contained): ${u}`);
  for (const f of failed) problems.push(`request failed: ${f}`);
  summary.ok = problems.length === 0;
  summary.problems = problems;
  console.log(JSON.stringify(summary, null, 2));
  if (problems.length) {
    for (const p of problems) console.error(`check-report: ${p}`);
    process.exitCode = 1;
  }
}
