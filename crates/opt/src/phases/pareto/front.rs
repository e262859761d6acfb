//! Fronts of objective vectors (every objective minimised): non-dominated sorting,
//! crowding distance, exact hypervolume (2–4 objectives) and the knee rule.
//!
//! Values are compared as they are: a design that collapses enters with +∞ objectives
//! (it is dominated by every design that stands). NaN is not an objective value; callers
//! map failures to +∞ before sorting.

/// Whether `a` dominates `b`: no worse in every objective, better in at least one.
/// Equal vectors do not dominate each other.
pub fn dominates(a: &[f64], b: &[f64]) -> bool {
    let mut better = false;
    for (x, y) in a.iter().zip(b) {
        if x > y {
            return false;
        }
        if x < y {
            better = true;
        }
    }
    better
}

/// Non-dominated sorting (Deb et al. 2002, the fast O(M N²) version): `rank[i]` of each
/// point, 1 for the front of points no other point dominates, 2 for the front of the
/// rest, and so on. Duplicates share their rank; a single point has rank 1.
pub fn nondominated_ranks(points: &[Vec<f64>]) -> Vec<usize> {
    let n = points.len();
    let mut dominated_by = vec![0usize; n];
    let mut dominates_list: Vec<Vec<usize>> = vec![Vec::new(); n];
    for i in 0..n {
        for j in i + 1..n {
            if dominates(&points[i], &points[j]) {
                dominates_list[i].push(j);
                dominated_by[j] += 1;
            } else if dominates(&points[j], &points[i]) {
                dominates_list[j].push(i);
                dominated_by[i] += 1;
            }
        }
    }
    let mut rank = vec![0usize; n];
    let mut current: Vec<usize> = (0..n).filter(|&i| dominated_by[i] == 0).collect();
    let mut r = 1;
    while !current.is_empty() {
        let mut next = Vec::new();
        for &i in &current {
            rank[i] = r;
            for &j in &dominates_list[i] {
                dominated_by[j] -= 1;
                if dominated_by[j] == 0 {
                    next.push(j);
                }
            }
        }
        next.sort_unstable();
        current = next;
        r += 1;
    }
    rank
}

/// Indices of the first front (rank 1), in index order.
pub fn first_front(points: &[Vec<f64>]) -> Vec<usize> {
    nondominated_ranks(points)
        .iter()
        .enumerate()
        .filter(|&(_, &r)| r == 1)
        .map(|(i, _)| i)
        .collect()
}

/// Crowding distance of each point of one front (Deb et al. 2002): per objective, the
/// points sorted by it (ties by index), the two ends get +∞ and every other point the
/// normalised distance between its two neighbours, summed over the objectives. An
/// objective whose values are all equal adds nothing; a front of one or two points, or
/// of points all equal, is all ends (+∞).
pub fn crowding_distance(front: &[Vec<f64>]) -> Vec<f64> {
    let n = front.len();
    let mut d = vec![0.0; n];
    if n <= 2 {
        return vec![f64::INFINITY; n];
    }
    let k = front[0].len();
    let mut spread = false;
    // m indexes the objective inside each point (front[a][m]), not the front
    #[allow(clippy::needless_range_loop)]
    for m in 0..k {
        let mut order: Vec<usize> = (0..n).collect();
        order.sort_by(|&a, &b| front[a][m].total_cmp(&front[b][m]).then(a.cmp(&b)));
        let lo = front[order[0]][m];
        let hi = front[order[n - 1]][m];
        let range = hi - lo;
        if !(range.is_finite() && range > 0.0) {
            continue;
        }
        spread = true;
        d[order[0]] = f64::INFINITY;
        d[order[n - 1]] = f64::INFINITY;
        for w in 1..n - 1 {
            d[order[w]] += (front[order[w + 1]][m] - front[order[w - 1]][m]) / range;
        }
    }
    if !spread {
        return vec![f64::INFINITY; n];
    }
    d
}

/// The exact hypervolume (Lebesgue measure) dominated by `points` and bounded by the
/// reference point `reference` (minimisation): the volume of the union of the boxes
/// [pᵢ, reference]. Points not strictly better than the reference in every objective add
/// nothing; dominated points and duplicates are allowed. One objective: the distance of
/// the best point to the reference; two: a sweep; three and more: slicing along the last
/// objective (exact; O(N^(k−1) log N), for fronts of a few hundred points).
pub fn hypervolume(points: &[Vec<f64>], reference: &[f64]) -> f64 {
    let k = reference.len();
    let inside: Vec<&[f64]> = points
        .iter()
        .map(Vec::as_slice)
        .filter(|p| p.len() == k && p.iter().zip(reference).all(|(a, r)| a < r))
        .collect();
    hv(&inside, reference)
}

fn hv(points: &[&[f64]], reference: &[f64]) -> f64 {
    let k = reference.len();
    if points.is_empty() || k == 0 {
        return 0.0;
    }
    match k {
        1 => {
            let best = points.iter().map(|p| p[0]).fold(f64::INFINITY, f64::min);
            reference[0] - best
        }
        2 => {
            let mut pts: Vec<&[f64]> = points.to_vec();
            pts.sort_by(|a, b| a[0].total_cmp(&b[0]).then(a[1].total_cmp(&b[1])));
            let mut area = 0.0;
            let mut prev = reference[1];
            for p in pts {
                if p[1] < prev {
                    area += (reference[0] - p[0]) * (prev - p[1]);
                    prev = p[1];
                }
            }
            area
        }
        _ => {
            // slices between consecutive values of the last objective: in each, the
            // (k−1)-D hypervolume of the points at or below the slice's bottom
            let mut pts: Vec<&[f64]> = points.to_vec();
            pts.sort_by(|a, b| a[k - 1].total_cmp(&b[k - 1]));
            let sub_ref = &reference[..k - 1];
            let mut vol = 0.0;
            let mut i = 0;
            while i < pts.len() {
                let z = pts[i][k - 1];
                let mut j = i;
                while j < pts.len() && pts[j][k - 1] == z {
                    j += 1;
                }
                let top = if j < pts.len() {
                    pts[j][k - 1]
                } else {
                    reference[k - 1]
                };
                let below: Vec<&[f64]> = pts[..j].iter().map(|p| &p[..k - 1]).collect();
                vol += hv(&below, sub_ref) * (top - z);
                i = j;
            }
            vol
        }
    }
}

/// The ideal (least) and nadir (largest) value of each of the `k` objectives over
/// `points`, in one pass (±∞ where there are none).
pub fn ideal_and_nadir<'a>(
    k: usize,
    points: impl IntoIterator<Item = &'a [f64]>,
) -> (Vec<f64>, Vec<f64>) {
    let mut lo = vec![f64::INFINITY; k];
    let mut hi = vec![f64::NEG_INFINITY; k];
    for p in points {
        for m in 0..k {
            lo[m] = lo[m].min(p[m]);
            hi[m] = hi[m].max(p[m]);
        }
    }
    (lo, hi)
}

/// The normalised objectives of a front: each objective mapped so that the front's best
/// value (the ideal) is 0 and its worst (the nadir) 1; an objective equal on the whole
/// front maps to 0.
pub fn normalised(front: &[Vec<f64>]) -> Vec<Vec<f64>> {
    let Some(first) = front.first() else {
        return Vec::new();
    };
    let k = first.len();
    let (lo, hi) = ideal_and_nadir(k, front.iter().map(Vec::as_slice));
    front
        .iter()
        .map(|p| {
            (0..k)
                .map(|m| {
                    let range = hi[m] - lo[m];
                    if range.is_finite() && range > 0.0 {
                        (p[m] - lo[m]) / range
                    } else {
                        0.0
                    }
                })
                .collect()
        })
        .collect()
}

/// The knee of a front (its points, every one non-dominated): the point farthest, on the
/// ideal side, from the hyperplane through the normalised extremes — with every objective
/// normalised to the front's ideal (0) and nadir (1) ([`normalised`]), the hyperplane
/// Σ f̂ = 1, so the knee is the point of least Σ f̂. With two objectives that hyperplane
/// is the line through the front's two end points (the end minimising one objective is
/// the worst in the other), the classical knee of the trade-off curve: the design where a
/// further gain in one objective starts to cost more (in units of each objective's range
/// over the front) than it gains. The rule is free of units and of parameters. Ties go
/// to the lowest index. `None` for an empty front.
pub fn knee(front: &[Vec<f64>]) -> Option<usize> {
    let norm = normalised(front);
    let mut best: Option<(usize, f64)> = None;
    for (i, p) in norm.iter().enumerate() {
        let s: f64 = p.iter().sum();
        if best.is_none_or(|(_, b)| s < b) {
            best = Some((i, s));
        }
    }
    best.map(|(i, _)| i)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pts(v: &[&[f64]]) -> Vec<Vec<f64>> {
        v.iter().map(|p| p.to_vec()).collect()
    }

    #[test]
    fn ranks_of_a_hand_made_set() {
        let p = pts(&[
            &[1.0, 5.0], // front
            &[2.0, 3.0], // front
            &[4.0, 1.0], // front
            &[3.0, 4.0], // dominated by (2, 3)
            &[5.0, 5.0], // dominated by (3, 4): rank 3
            &[2.0, 3.0], // duplicate of a front point: front too
        ]);
        assert_eq!(nondominated_ranks(&p), vec![1, 1, 1, 2, 3, 1]);
        assert_eq!(first_front(&p), vec![0, 1, 2, 5]);
    }

    #[test]
    fn ties_in_one_objective_dominate() {
        // equal first objective, better second: (1, 2) dominates (1, 3)
        let p = pts(&[&[1.0, 3.0], &[1.0, 2.0]]);
        assert_eq!(nondominated_ranks(&p), vec![2, 1]);
    }

    #[test]
    fn single_point_and_all_equal() {
        assert_eq!(nondominated_ranks(&pts(&[&[3.0, 4.0]])), vec![1]);
        let same = pts(&[&[2.0, 2.0], &[2.0, 2.0], &[2.0, 2.0]]);
        assert_eq!(nondominated_ranks(&same), vec![1, 1, 1]);
        assert_eq!(knee(&same), Some(0));
        assert_eq!(knee(&pts(&[&[3.0, 4.0]])), Some(0));
        assert_eq!(knee(&[]), None);
        assert!(crowding_distance(&same).iter().all(|d| d.is_infinite()));
    }

    #[test]
    fn collapsed_designs_rank_last() {
        let inf = f64::INFINITY;
        let p = pts(&[&[inf, inf], &[1.0, 1.0]]);
        assert_eq!(nondominated_ranks(&p), vec![2, 1]);
    }

    #[test]
    fn crowding_of_a_hand_made_front() {
        // on the line f1 + f2 = 4: ends infinite; middle points (range 4 in each)
        let f = pts(&[&[0.0, 4.0], &[1.0, 3.0], &[3.0, 1.0], &[4.0, 0.0]]);
        let d = crowding_distance(&f);
        assert!(d[0].is_infinite() && d[3].is_infinite());
        // point 1: neighbours 0 and 2 → (3 − 0)/4 + (4 − 1)/4 = 1.5
        assert!((d[1] - 1.5).abs() < 1e-15);
        assert!((d[2] - 1.5).abs() < 1e-15);
    }

    #[test]
    fn hypervolume_2d_by_hand() {
        let f = pts(&[&[1.0, 3.0], &[2.0, 2.0], &[3.0, 1.0]]);
        // reference (4, 4): staircase 3·1 + 2·1 + 1·1 = 6
        assert_eq!(hypervolume(&f, &[4.0, 4.0]), 6.0);
        // dominated points, duplicates and points beyond the reference change nothing
        let mut g = f.clone();
        g.extend(pts(&[&[3.0, 3.0], &[2.0, 2.0], &[5.0, 0.5], &[0.5, 4.0]]));
        assert_eq!(hypervolume(&g, &[4.0, 4.0]), 6.0);
        assert_eq!(hypervolume(&[], &[4.0, 4.0]), 0.0);
    }

    #[test]
    fn hypervolume_3d_and_4d_by_inclusion_exclusion() {
        // two boxes [p, r] in 3-D: |A| + |B| − |A ∩ B|
        let a = [1.0, 2.0, 3.0];
        let b = [2.0, 1.0, 2.0];
        let r = [4.0, 4.0, 4.0];
        let vol = |p: &[f64]| p.iter().zip(&r).map(|(x, y)| y - x).product::<f64>();
        let meet: Vec<f64> = a.iter().zip(&b).map(|(x, y)| f64::max(*x, *y)).collect();
        let want = vol(&a) + vol(&b) - vol(&meet);
        let got = hypervolume(&[a.to_vec(), b.to_vec()], &r);
        assert!((got - want).abs() < 1e-12, "{got} vs {want}");
        // 4-D: three boxes, inclusion–exclusion over every pair and the triple
        let r4 = [5.0; 4];
        let q = pts(&[
            &[1.0, 2.0, 3.0, 4.0],
            &[4.0, 3.0, 2.0, 1.0],
            &[2.0, 2.0, 2.0, 2.0],
        ]);
        let v4 = |p: &[f64]| p.iter().zip(&r4).map(|(x, y)| y - x).product::<f64>();
        let m = |x: &[f64], y: &[f64]| {
            x.iter()
                .zip(y)
                .map(|(a, b)| f64::max(*a, *b))
                .collect::<Vec<_>>()
        };
        let want = v4(&q[0]) + v4(&q[1]) + v4(&q[2])
            - v4(&m(&q[0], &q[1]))
            - v4(&m(&q[0], &q[2]))
            - v4(&m(&q[1], &q[2]))
            + v4(&m(&m(&q[0], &q[1]), &q[2]));
        let got = hypervolume(&q, &r4);
        assert!((got - want).abs() < 1e-12, "{got} vs {want}");
    }

    #[test]
    fn hypervolume_3d_of_a_monte_carlo_checked_set() {
        // a set whose union is known in closed form: a 2×2×2 staircase of unit cubes
        // below the plane x + y + z ≤ 4 (reference 3): cubes at (i, j, k) with
        // i + j + k ≤ 2 → the corners (0,0,2), (0,2,0), (2,0,0), (0,1,1), (1,0,1), (1,1,0)
        let f = pts(&[
            &[0.0, 0.0, 2.0],
            &[0.0, 2.0, 0.0],
            &[2.0, 0.0, 0.0],
            &[0.0, 1.0, 1.0],
            &[1.0, 0.0, 1.0],
            &[1.0, 1.0, 0.0],
        ]);
        // unit cells (a, b, c) ∈ {0,1,2}³ covered: some corner ≤ (a, b, c) componentwise
        let mut cells = 0;
        for a in 0..3 {
            for b in 0..3 {
                for c in 0..3 {
                    let cell = [a as f64, b as f64, c as f64];
                    if f.iter().any(|p| p.iter().zip(&cell).all(|(x, y)| x <= y)) {
                        cells += 1;
                    }
                }
            }
        }
        assert_eq!(hypervolume(&f, &[3.0, 3.0, 3.0]), cells as f64);
    }

    #[test]
    fn knee_of_a_convex_front() {
        // the ends (0, 10) and (10, 0); the knee bulges most towards the ideal
        let f = pts(&[
            &[0.0, 10.0],
            &[1.0, 4.0],
            &[3.0, 2.0],
            &[6.0, 1.0],
            &[10.0, 0.0],
        ]);
        // Σ f̂: 1, 0.5, 0.5, 0.7, 1 → first of the tie, (1, 4)
        assert_eq!(knee(&f), Some(1));
        // the rule does not depend on units: scale one objective by 1000
        let g: Vec<Vec<f64>> = f.iter().map(|p| vec![p[0] * 1000.0, p[1]]).collect();
        assert_eq!(knee(&g), knee(&f));
        // a linear front has no knee but a tie: the lowest index
        let line = pts(&[&[0.0, 2.0], &[1.0, 1.0], &[2.0, 0.0]]);
        assert_eq!(knee(&line), Some(0));
    }
}
