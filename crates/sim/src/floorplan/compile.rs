//! A scene in plan compiled into a [`Plan`]: the floors' DOFs (ux, uy, θ of each floor's
//! origin, floor by floor), then one DOF per damper with mass; every line's storey spring,
//! yield law and damper an element between the line's points on two floors
//! ([`crate::kinematics::Kin`]); the ground's influence from the component's direction;
//! the drifts of every line and of the plan's edges, and the floors' centres of mass and
//! rotations, as the responses' measures.
//!
//! The same reductions as a chain's (docs/MODEL.md § Scenes and plans): a damper at zero
//! slip load is no element, a locked one is its brace (its mass joins the floor along the
//! line), a massless one an elastic–perfectly plastic element without a DOF.

use super::build::{line_ends, line_point};
use super::model::{FloorPlan, cos_sin};
use super::scene::FloorPlanScene;
use crate::error::SimError;
use crate::kinematics::{Kin, add_between};
use crate::plan::{
    BaseRows, Contact, ContactKind, ContactRole, FloorLink, Labels, Plan, SecondGround,
    check_step_count,
};
use nalgebra::{DMatrix, DVector};
use std::sync::Arc;

/// A damper's place: its line and storey (0-based).
struct Site {
    line: usize,
    storey: usize,
}

/// Compiles a scene in plan into the plan every general integrator steps.
///
/// Each ground component acts along its angle to the plan's x axis; a second one is the
/// plan's [`SecondGround`], applied with the first.
pub fn compile(scene: &FloorPlanScene) -> Result<Plan, SimError> {
    check_step_count(scene.method.dt, scene.duration)?;
    let b: &FloorPlan = &scene.building;
    let n = b.storeys();
    let nf = 3 * n;
    if scene.ground.len() > 2 {
        return Err(SimError::Scene(format!(
            "{}: {} ground components; a scene takes at most the two horizontal ones",
            scene.name,
            scene.ground.len()
        )));
    }
    let psi = scene.ground.first().map_or(0.0, |g| g.angle);
    let (gc, gs) = cos_sin(psi);
    // the kinematic weights (c, s, lever) of the dampers with a DOF, for each ground
    // component's influence on them and the base's rigid motions
    let mut dof_dirs: Vec<(usize, [f64; 3])> = Vec::new();
    let bilinear = scene.method.name == crate::scene::MethodName::Bilinear;
    let mut notes = vec![format!(
        "building in plan: {n} floors x 3 DOFs (ux, uy, rotation of the plan's origin), {} lines",
        b.lines.len()
    )];
    // Sites of every damper the file places, in line order: their slots stay the same
    // whatever the slip loads (a free damper keeps its slot, at zero).
    let sites: Vec<Site> = b
        .lines
        .iter()
        .enumerate()
        .flat_map(|(l, line)| {
            line.dissipators
                .iter()
                .enumerate()
                .filter(|(_, d)| d.is_some())
                .map(move |(f, _)| Site { line: l, storey: f })
        })
        .collect();
    let drop_free = |d: &crate::building::Dissipator| d.is_free() && !scene.outputs.sensitivities;
    // DOFs: the floors', then one per damper with mass.
    let mut n_dof = nf;
    let mut dof_of = vec![None; sites.len()];
    for (s, site) in sites.iter().enumerate() {
        let Some(d) = b.lines[site.line].dissipators[site.storey] else {
            continue;
        };
        if !(bilinear || drop_free(&d) || d.is_locked() || d.mass == 0.0) {
            dof_of[s] = Some(n_dof);
            n_dof += 1;
        }
    }
    let mut mass = DMatrix::zeros(n_dof, n_dof);
    let mut damping = DMatrix::zeros(n_dof, n_dof);
    let mut stiffness = DMatrix::zeros(n_dof, n_dof);
    mass.view_mut((0, 0), (nf, nf)).copy_from(&b.mass);
    damping.view_mut((0, 0), (nf, nf)).copy_from(&b.damping);
    stiffness.view_mut((0, 0), (nf, nf)).copy_from(&b.stiffness);
    // The lines' storey dashpots, between each storey's two points of the line
    for line in &b.lines {
        for (f, &c) in line.dashpots.iter().enumerate() {
            if c > 0.0 {
                let (top, bottom) = line_ends(line, f);
                add_between(&mut damping, &top, &bottom, c);
            }
        }
    }
    if b.lines.iter().any(|l| l.dashpots.iter().any(|c| *c > 0.0)) {
        notes.push("storey dashpots of the lines: viscous elements along the lines, added to the frame damping".into());
    }
    // P-Δ: each storey's geometric stiffness on its relative motion (Δ of the floor's
    // ux, uy, θ over the floor below's; the ground's is zero), subtracted
    if let Some(pd) = &b.p_delta {
        for (f, block) in pd.blocks.iter().enumerate() {
            let top = 3 * f;
            for i in 0..3 {
                for j in 0..3 {
                    let g = block[i][j];
                    stiffness[(top + i, top + j)] -= g;
                    if f > 0 {
                        let bot = top - 3;
                        stiffness[(bot + i, bot + j)] -= g;
                        stiffness[(top + i, bot + j)] += g;
                        stiffness[(bot + i, top + j)] += g;
                    }
                }
            }
        }
        notes.push(format!(
            "P-Delta: each storey's gravity load [{}] N spread as the mass above it; geometric stiffness on the storey's two translations and its twist",
            pd.loads
                .iter()
                .map(|v| format!("{v:.6e}"))
                .collect::<Vec<_>>()
                .join(", ")
        ));
    }
    let mut contacts = Vec::new();
    let mut contact_x0 = Vec::new();
    let label = |s: &Site| format!("{}/{}", b.lines[s.line].name, s.storey + 1);
    for (s, site) in sites.iter().enumerate() {
        let line = &b.lines[site.line];
        let Some(mut d) = line.dissipators[site.storey] else {
            continue;
        };
        if bilinear {
            d.mass = 0.0;
        }
        let (top, bottom) = line_ends(line, site.storey);
        if drop_free(&d) {
            notes.push(format!(
                "{}: slip load 0 -> brace disconnected (no element)",
                label(site)
            ));
            continue;
        }
        if d.is_locked() {
            let g = line_point(line, site.storey);
            add_between(&mut mass, &g, &Kin::GROUND, d.mass);
            add_between(&mut stiffness, &top, &bottom, d.brace_stiffness);
            add_between(&mut damping, &top, &bottom, d.brace_damping);
            notes.push(format!(
                "{}: locked -> brace k' = {:.6e} N/m along the line, m' = {} kg moving with the floor",
                label(site),
                d.brace_stiffness,
                d.mass
            ));
            continue;
        }
        let kind = match dof_of[s] {
            Some(dof) => {
                mass[(dof, dof)] = d.mass;
                add_between(&mut stiffness, &Kin::dof(dof), &bottom, d.brace_stiffness);
                add_between(&mut damping, &Kin::dof(dof), &bottom, d.brace_damping);
                dof_dirs.push((dof, line.weights()));
                notes.push(format!(
                    "{}: friction contact, dissipator DOF {dof} (m' = {} kg, k' = {:.6e} N/m), bounds [{:.6e}, {:.6e}] N",
                    label(site),
                    d.mass,
                    d.brace_stiffness,
                    d.lower,
                    d.upper
                ));
                ContactKind::Dof { dof }
            }
            None => {
                notes.push(format!(
                    "{}: elastic-perfectly plastic element along the line (k' = {:.6e} N/m, bounds [{:.6e}, {:.6e}] N), no DOF",
                    label(site),
                    d.brace_stiffness,
                    d.lower,
                    d.upper
                ));
                ContactKind::Epp
            }
        };
        contact_x0.push((0.0, 0.0));
        contacts.push(Contact {
            role: ContactRole::Damper,
            floor: site.storey,
            slot: s,
            top,
            bottom,
            kind,
            lower: d.lower,
            upper: d.upper,
            brace_stiffness: d.brace_stiffness,
            brace_damping: d.brace_damping,
        });
    }
    // Yielding storeys of the lines: αk stays in K, (1−α)k yielding at (1−α)Fy is an
    // elastic–perfectly plastic element between the line's two points.
    let mut plastic = 0;
    let mut plastic_names = Vec::new();
    for line in &b.lines {
        for (f, y) in line.storey_yield.iter().enumerate() {
            let Some(y) = y else { continue };
            let (top, bottom) = line_ends(line, f);
            let kp = (1.0 - y.post_yield_ratio) * y.stiffness;
            let fp = (1.0 - y.post_yield_ratio) * y.yield_shear;
            add_between(&mut stiffness, &top, &bottom, -kp);
            contact_x0.push((0.0, 0.0));
            contacts.push(Contact {
                role: ContactRole::Storey,
                floor: f,
                slot: sites.len() + plastic,
                top,
                bottom,
                kind: ContactKind::Epp,
                lower: -fp,
                upper: fp,
                brace_stiffness: kp,
                brace_damping: 0.0,
            });
            plastic += 1;
            plastic_names.push(format!("{}/{}", line.name, f + 1));
            notes.push(format!(
                "{}/{}: yields (k = {:.6e} N/m, Fy = {:.6e} N, alpha = {}) -> elastic-perfectly plastic element along the line",
                line.name,
                f + 1,
                y.stiffness,
                y.yield_shear,
                y.post_yield_ratio
            ));
        }
    }
    let mut initial = stiffness.clone();
    for ct in contacts.iter().filter(|c| c.kind == ContactKind::Epp) {
        add_between(&mut initial, &ct.top, &ct.bottom, ct.brace_stiffness);
    }
    if initial.cholesky().is_none() {
        return Err(SimError::NotPositiveDefinite {
            what: "assembled stiffness matrix of the building in plan".into(),
            hint: " (check the lines' stiffnesses and the brace stiffnesses)".into(),
        });
    }
    // Measures: every line's storeys, then the plan's edges; each floor's centre of mass
    // along x and y and its rotation.
    let mut drifts = Vec::new();
    let mut drift_names = Vec::new();
    let mut drift_storeys = Vec::new();
    let mut heights = Vec::new();
    let mut yield_drift = Vec::new();
    let mut collapse = Vec::new();
    let storey_h = |f: usize| b.storey_heights.as_ref().map(|h| h[f]);
    for line in &b.lines {
        for f in 0..n {
            drifts.push(line_ends(line, f));
            drift_names.push(format!("{}/{}", line.name, f + 1));
            drift_storeys.push(f);
            heights.push(storey_h(f));
            yield_drift.push(line.storey_yield[f].map(|y| y.yield_drift()));
            collapse.push(b.collapse_drift.as_ref().map_or(f64::INFINITY, |c| c[f]));
        }
    }
    let edges = b.plan_size.map(|[lx, ly]| {
        let mut per_storey = Vec::with_capacity(n);
        // (name, direction (0 = x, 1 = y), the coordinate across it)
        let sides = [
            ("y=0", 0, 0.0),
            ("y=Ly", 0, ly),
            ("x=0", 1, 0.0),
            ("x=Lx", 1, lx),
        ];
        for f in 0..n {
            let mut idx = [0; 4];
            for (k, (side, dir, at)) in sides.iter().enumerate() {
                // along x at y = at moves by ux − at·θ; along y at x = at by uy + at·θ
                let point = |g: usize| {
                    if *dir == 0 {
                        Kin::weighted(&[(3 * g, 1.0), (3 * g + 2, -at)])
                    } else {
                        Kin::weighted(&[(3 * g + 1, 1.0), (3 * g + 2, *at)])
                    }
                };
                let bottom = if f == 0 { Kin::GROUND } else { point(f - 1) };
                idx[k] = drifts.len();
                drifts.push((point(f), bottom));
                drift_names.push(format!(
                    "edge {side} ({})/{}",
                    if *dir == 0 { "x" } else { "y" },
                    f + 1
                ));
                drift_storeys.push(f);
                heights.push(storey_h(f));
                yield_drift.push(None);
                collapse.push(f64::INFINITY);
            }
            per_storey.push(idx);
        }
        per_storey
    });
    // A unit ground displacement along ψ moves every floor's origin by (cos ψ, sin ψ)
    // without turning it, and a damper's DOF by its projection on the line, cos(φ − ψ).
    let influence_of = |psi: f64| {
        let (c, s) = cos_sin(psi);
        let mut r = DVector::zeros(n_dof);
        for f in 0..n {
            r[3 * f] = c;
            r[3 * f + 1] = s;
        }
        for &(dof, [lc, ls, _]) in &dof_dirs {
            r[dof] = lc * c + ls * s;
        }
        r
    };
    let influence = influence_of(psi);
    let second_influence = scene.ground.get(1).map(|g| influence_of(g.angle));
    // The base's rigid motions: translations along x and y are the influences at 0° and
    // 90°; a unit rotation about the building's centre of mass P (the floors' masses'
    // centroid) turns every floor, moves each floor's origin by (P_y, −P_x) and a damper's
    // DOF by its line's lever about P.
    let total: f64 = b.floors.iter().map(|fl| fl.mass).sum();
    let about = [0, 1].map(|k| {
        b.floors
            .iter()
            .map(|fl| fl.mass * fl.centre[k])
            .sum::<f64>()
            / total
    });
    let base = {
        let mut rot = DVector::zeros(n_dof);
        for f in 0..n {
            rot[3 * f] = about[1];
            rot[3 * f + 1] = -about[0];
            rot[3 * f + 2] = 1.0;
        }
        for &(dof, [c, s, lever]) in &dof_dirs {
            rot[dof] = lever - (about[0] * s - about[1] * c);
        }
        let rows = [
            influence_of(0.0),
            influence_of(std::f64::consts::FRAC_PI_2),
            rot,
        ]
        .map(|e| &mass * e);
        let share = |r: Option<&DVector<f64>>| [0, 1, 2].map(|k| r.map_or(0.0, |r| rows[k].dot(r)));
        BaseRows {
            about,
            first: share(scene.ground.first().map(|_| &influence)),
            second: share(second_influence.as_ref()),
            rows,
        }
    };
    // Each floor's centre of mass (x, y) and rotation, then the named points' x and y on
    // every floor; a point (x, y) of a floor moves by (ux − y·θ, uy + x·θ). `dirs` is each
    // point's direction (0 x, 1 y, 2 the rotation), for each component's influence.
    let mut points = Vec::with_capacity(nf + 2 * n * b.points.len());
    let mut point_names = Vec::with_capacity(points.capacity());
    let mut dirs: Vec<usize> = Vec::with_capacity(points.capacity());
    let along = |f: usize, [x, y]: [f64; 2]| {
        [
            Kin::weighted(&[(3 * f, 1.0), (3 * f + 2, -y)]),
            Kin::weighted(&[(3 * f + 1, 1.0), (3 * f + 2, x)]),
        ]
    };
    for (f, fl) in b.floors.iter().enumerate() {
        let [px, py] = along(f, fl.centre);
        points.extend([
            (px, gc),
            (py, gs),
            (Kin::weighted(&[(3 * f + 2, 1.0)]), 0.0),
        ]);
        dirs.extend([0, 1, 2]);
        point_names.extend([
            format!("{} x", f + 1),
            format!("{} y", f + 1),
            format!("{} rot", f + 1),
        ]);
    }
    for f in 0..n {
        for (name, at) in &b.points {
            let [px, py] = along(f, *at);
            points.extend([(px, gc), (py, gs)]);
            dirs.extend([0, 1]);
            point_names.extend([format!("{} {name} x", f + 1), format!("{} {name} y", f + 1)]);
        }
    }
    let steps = ((scene.duration / scene.method.dt * (1.0 - 1e-9)).ceil() as usize).max(1);
    for g in scene.ground.iter().skip(1) {
        notes.push(format!(
            "second ground component: {} at {:.3} deg from x, applied with the first (PGA = {:.4} m/s^2)",
            g.record.name(),
            g.angle.to_degrees(),
            g.record.pga()
        ));
    }
    match scene.ground.first() {
        Some(g) => notes.push(format!(
            "ground motion: {} at {:.3} deg from x ({} samples at dt = {} s, PGA = {:.4} m/s^2)",
            g.record.name(),
            g.angle.to_degrees(),
            g.record.len(),
            g.record.dt(),
            g.record.pga()
        )),
        None => notes.push("ground motion: none".into()),
    }
    notes.push(format!(
        "method {}, dt = {:.6e} s (bare T1 = {:.4} s), {steps} steps; {} DOFs, {} friction contacts, {} plastic elements",
        scene.method.name.as_str(),
        scene.method.dt,
        b.t1(),
        n_dof,
        contacts.len() - plastic,
        plastic
    ));
    let any_collapse = b.collapse_drift.is_some();
    Ok(Plan {
        name: scene.name.clone(),
        floors: n,
        mass,
        damping,
        stiffness,
        contacts,
        damper_slots: sites.len(),
        drifts,
        points,
        influence,
        chain: false,
        labels: Some(Arc::new(Labels {
            drifts: drift_names,
            drift_storeys,
            points: point_names,
            dampers: sites.iter().map(label).collect(),
            plastic: plastic_names,
            edges,
        })),
        frame_dofs: nf,
        links: vec![FloorLink::None; n],
        storey_heights: heights.iter().copied().collect::<Option<Vec<f64>>>(),
        record: scene.ground.first().map(|g| g.record.clone()),
        second: scene
            .ground
            .get(1)
            .zip(second_influence)
            .map(|(g, influence)| SecondGround {
                record: g.record.clone(),
                influence,
                points: {
                    let (c, s) = cos_sin(g.angle);
                    dirs.iter().map(|d| [c, s, 0.0][*d]).collect()
                },
            }),
        base: Some(Arc::new(base)),
        harmonic: None,
        u0: vec![0.0; n_dof],
        v0: vec![0.0; n_dof],
        contact_x0,
        method: scene.method,
        steps,
        outputs: scene.outputs,
        t1: b.t1(),
        yield_drift,
        collapse_drift: any_collapse.then_some(collapse),
        notes,
    })
}
