//! Each mode set's operators: the mode matrix A (stuck dissipators with mass as
//! constraints, sliding contacts at their bounds, massless ones as states), the force and
//! slip-rate rows, the event functions, the substep grid, and the observed functions'
//! rows ([`observed_peak`] reads their peaks).

use super::kernels::SparseRows;
use super::model::{EventFn, Mode, ModeOps, Model, Scale};
use super::params::SUBSTEP_PHASE;
use crate::plan::{ContactKind, Plan};
use crate::response::Peaks;
use nalgebra::{DMatrix, DVector};
use std::cell::OnceCell;

impl Model<'_> {
    pub(super) fn build(&self, modes: &[Mode]) -> ModeOps {
        let plan = self.plan;
        let lay = &self.lay;
        let (n, dim) = (lay.n, lay.dim);
        let nc = plan.contacts.len();
        let mut f = self.f0.clone();
        let mut force = DMatrix::zeros(nc, dim);
        let mut xdot = DMatrix::zeros(nc, dim);
        let mut stuck = Vec::new();
        for (c, ct) in plan.contacts.iter().enumerate() {
            match (modes[c], ct.kind) {
                (Mode::Upper, _) => force[(c, lay.i_one)] = ct.upper,
                (Mode::Lower, _) => force[(c, lay.i_one)] = ct.lower,
                (Mode::Stuck, ContactKind::Dof { .. }) => stuck.push(c),
                (Mode::Stuck, ContactKind::Epp) => {
                    let s = lay.epp_slot[c].expect("EPP contacts have a slot");
                    force[(c, s)] += ct.brace_stiffness;
                    for (i, w) in ct.top.entries() {
                        force[(c, n + i)] += ct.brace_damping * w;
                    }
                    for (j, w) in ct.bottom.entries() {
                        force[(c, j)] -= ct.brace_stiffness * w;
                        force[(c, n + j)] -= ct.brace_damping * w;
                    }
                }
            }
            if let Some(s) = lay.epp_slot[c] {
                match modes[c] {
                    Mode::Stuck => {
                        for (i, w) in ct.top.entries() {
                            xdot[(c, n + i)] = w;
                        }
                    }
                    Mode::Upper | Mode::Lower => {
                        for (j, w) in ct.bottom.entries() {
                            xdot[(c, n + j)] = w;
                        }
                        if ct.brace_damping > 0.0 {
                            let bound = force[(c, lay.i_one)];
                            let r = 1.0 / ct.brace_damping;
                            xdot[(c, lay.i_one)] += bound * r;
                            xdot[(c, s)] -= ct.brace_stiffness * r;
                            for (j, w) in ct.bottom.entries() {
                                xdot[(c, j)] += ct.brace_stiffness * r * w;
                            }
                        }
                    }
                }
            }
            if !(modes[c] == Mode::Stuck && matches!(ct.kind, ContactKind::Dof { .. })) {
                // f −= b_c ⊗ force_c
                let row = force.row(c).into_owned();
                for i in 0..n {
                    let b = self.bcols[c][i];
                    if b != 0.0 {
                        for j in 0..dim {
                            f[(i, j)] -= b * row[j];
                        }
                    }
                }
            }
        }
        let minv_f = &self.minv * &f;
        let (acc, proj) = if stuck.is_empty() {
            (minv_f, None)
        } else {
            let s = stuck.len();
            let mut bs = DMatrix::zeros(n, s);
            for (k, &c) in stuck.iter().enumerate() {
                bs.set_column(k, &self.bcols[c]);
            }
            let y = &self.minv * &bs;
            let ws = bs.transpose() * &y;
            let ws = (&ws + ws.transpose()) * 0.5;
            let wsinv = ws
                .cholesky()
                .expect("B_SᵀM⁻¹B_S is SPD: contact columns are independent")
                .inverse();
            let lam = &wsinv * (bs.transpose() * &minv_f);
            for (k, &c) in stuck.iter().enumerate() {
                force.set_row(c, &lam.row(k));
            }
            let proj = DMatrix::identity(n, n) - &y * &wsinv * bs.transpose();
            (minv_f - &y * &lam, Some(proj))
        };
        let mut a = DMatrix::zeros(dim, dim);
        for i in 0..n {
            a[(i, n + i)] = 1.0;
        }
        a.view_mut((n, 0), (n, dim)).copy_from(&acc);
        let mut slip_rate = DMatrix::zeros(nc, dim);
        for (c, ct) in plan.contacts.iter().enumerate() {
            for (i, w) in ct.top.entries() {
                slip_rate[(c, n + i)] = w;
            }
            match (ct.kind, lay.epp_slot[c]) {
                (ContactKind::Dof { dof }, _) => slip_rate[(c, n + dof)] -= 1.0,
                (ContactKind::Epp, Some(s)) => {
                    a.set_row(s, &xdot.row(c));
                    let r = slip_rate.row(c) - xdot.row(c);
                    slip_rate.set_row(c, &r);
                }
                (ContactKind::Epp, None) => unreachable!("EPP contacts have a slot"),
            }
        }
        a[(lay.i_ag, lay.i_slope)] = 1.0;
        if let Some((i_ag2, i_slope2)) = lay.second {
            a[(i_ag2, i_slope2)] = 1.0;
        }
        a[(lay.i_sin, lay.i_cos)] = self.omega_h;
        a[(lay.i_cos, lay.i_sin)] = -self.omega_h;
        let mut events = Vec::new();
        for (c, ct) in plan.contacts.iter().enumerate() {
            if ct.lower == ct.upper {
                // Zero-width bounds (μN = 0 kept in an unreduced plan): the force is that
                // value whatever the contact does; no events.
                continue;
            }
            let bound_scale = Scale::Force(
                [ct.upper, ct.lower]
                    .iter()
                    .filter(|b| b.is_finite())
                    .fold(0.0f64, |m, b| m.max(b.abs())),
            );
            match modes[c] {
                Mode::Stuck => {
                    if ct.upper.is_finite() {
                        let mut row = -force.row(c).transpose();
                        row[lay.i_one] += ct.upper;
                        events.push(EventFn {
                            contact: c,
                            row,
                            scale: bound_scale,
                        });
                    }
                    if ct.lower.is_finite() {
                        let mut row = force.row(c).transpose();
                        row[lay.i_one] -= ct.lower;
                        events.push(EventFn {
                            contact: c,
                            row,
                            scale: bound_scale,
                        });
                    }
                }
                Mode::Upper => events.push(EventFn {
                    contact: c,
                    row: slip_rate.row(c).transpose(),
                    scale: Scale::Velocity,
                }),
                Mode::Lower => events.push(EventFn {
                    contact: c,
                    row: -slip_rate.row(c).transpose(),
                    scale: Scale::Velocity,
                }),
            }
        }
        let dt = plan.method.dt;
        let rho = self.bound(Some(modes));
        let delta_max = if rho > 0.0 {
            SUBSTEP_PHASE / rho
        } else {
            f64::INFINITY
        };
        // Substeps per output step; where one output step is shorter than δ_max, the
        // frame of q output steps is cut into substeps of s output steps each, s the
        // largest divisor of q with s·Δt ≤ δ_max, so output steps are grid points.
        let per_out = if delta_max.is_finite() {
            ((dt / delta_max) * (1.0 - 1e-12)).ceil().max(1.0) as usize
        } else {
            1
        };
        let q = self.frame_steps;
        let (per_step, out_steps) = if per_out > 1 || q == 1 {
            (q * per_out, usize::from(per_out == 1))
        } else {
            let s = (1..=q)
                .rev()
                .find(|&s| q.is_multiple_of(s) && s as f64 * dt <= delta_max * (1.0 - 1e-12))
                .unwrap_or(1);
            (q / s, s)
        };
        let prepare_after = dim + events.len() + plan.drifts.len();
        let acc_rows = a.rows(n, n).transpose();
        // The observed functions' bounds are worth testing on a substep when they cost
        // less than the output steps inside it they can spare (a product with exp(A Δt)
        // and the observation, each).
        let obs_rows = if out_steps >= 2
            && 2 * (plan.observed_contacts_offset() + nc) * dim < (out_steps - 1) * (dim + n) * dim
        {
            self.observed_rows(&acc_rows)
        } else {
            DMatrix::zeros(dim, 0)
        };
        let a_rows = SparseRows::of(&a);
        let event_abs = events.iter().map(|e| e.row.abs()).collect();
        ModeOps {
            event_abs,
            obs_rows,
            a_rows,
            a,
            acc_rows,
            force: force.transpose(),
            slip_rate: slip_rate.transpose(),
            xdot: xdot.transpose(),
            events,
            proj,
            delta_max,
            per_step,
            out_steps,
            h: (q as f64 * dt) / per_step as f64,
            prepare_after,
            stepping: OnceCell::new(),
        }
    }
}

/// The current sampled peak of observed function `o` (the order of
/// [`ModeOps::obs_rows`]).
#[inline]
pub(super) fn observed_peak(plan: &Plan, peaks: &Peaks, o: usize) -> f64 {
    let (nd, np) = (plan.drifts.len(), plan.points.len());
    match o {
        _ if o < nd => peaks.drift[o],
        _ if o < nd + np => peaks.displacement[o - nd],
        _ if o < nd + 2 * np => peaks.abs_acceleration[o - nd - np],
        _ if o == nd + 2 * np => peaks.base_shear,
        _ => peaks.slip[plan.contacts[o - nd - 2 * np - 1].slot],
    }
}

impl Model<'_> {
    /// The rows of [`ModeOps::obs_rows`] from the mode set's acceleration rows
    /// (`acc_rows`, dim × n): the same quantities the output steps observe.
    fn observed_rows(&self, acc_rows: &DMatrix<f64>) -> DMatrix<f64> {
        let plan = self.plan;
        let lay = &self.lay;
        let (n, dim) = (lay.n, lay.dim);
        let (nd, np) = (plan.drifts.len(), plan.points.len());
        let oc = plan.observed_contacts_offset();
        let mut rows = DMatrix::zeros(dim, oc + plan.contacts.len());
        for (i, (top, bottom)) in plan.drifts.iter().enumerate() {
            let col = rows.column_mut(i);
            let mut col = col;
            top.add(col.as_mut_slice(), 1.0);
            bottom.add(col.as_mut_slice(), -1.0);
        }
        for (i, (point, ground)) in plan.points.iter().enumerate() {
            point.add(rows.column_mut(nd + i).as_mut_slice(), 1.0);
            let mut a = DVector::zeros(dim);
            for (j, w) in point.entries() {
                a.axpy(w, &acc_rows.column(j), 1.0);
            }
            a[lay.i_ag] += ground;
            if let (Some((i_ag2, _)), Some(g2)) = (lay.second, &plan.second) {
                a[i_ag2] += g2.points[i];
            }
            rows.set_column(nd + np + i, &a);
        }
        // Base shear Σ mᵢ(aᵢ + a_g) − p over every DOF (as `base_shear`).
        let mut v = DVector::zeros(dim);
        for i in 0..n {
            v.axpy(self.mr[i], &acc_rows.column(i), 1.0);
        }
        v[lay.i_ag] += plan.influence_mass();
        if let Some((i_ag2, _)) = lay.second {
            v[i_ag2] += plan.cross_mass();
        }
        if let Some(h) = &plan.harmonic {
            v[lay.i_sin] -= h.amplitude;
        }
        rows.set_column(oc - 1, &v);
        for (c, ct) in plan.contacts.iter().enumerate() {
            let col = oc + c;
            ct.top.add(rows.column_mut(col).as_mut_slice(), 1.0);
            match (ct.kind, lay.epp_slot[c]) {
                (ContactKind::Dof { dof }, _) => rows[(dof, col)] -= 1.0,
                (_, Some(s)) => rows[(s, col)] -= 1.0,
                (ContactKind::Epp, None) => {}
            }
        }
        rows
    }
}
