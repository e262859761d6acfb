//! The shear buildings `slipload bench` times against their storey count, as building
//! JSON (the bench and the benches of this crate build the same frames from here).

/// The frame damping of a bench shear building, 2 % in its first mode.
#[derive(Debug, Clone, Copy)]
pub enum ShearDamping {
    /// 2 % in every mode (a full damping matrix).
    Modal,
    /// Rayleigh, 2 % in the first two modes (banded: C = αM + βK).
    Rayleigh,
    /// Storey dashpots proportional to the storey stiffness, 2 % in the first mode
    /// (banded).
    Storey,
}

/// A uniform shear building of `n` storeys: 5e5 kg floors, storey stiffness giving
/// T₁ = 0.1·n s, 3.5 m storeys, and on every floor an m′ = 0 dissipator with k′ = 2k and
/// a slip load of 5 % of the weight above it; frame damping `damping`.
pub fn shear_building_damped(n: usize, damping: ShearDamping) -> String {
    let m = 5e5;
    let t1 = 0.1 * n as f64;
    let w1 = 2.0 * std::f64::consts::PI / t1;
    let s = (std::f64::consts::PI / (2.0 * (2 * n + 1) as f64)).sin();
    let k = m * (w1 / (2.0 * s)).powi(2);
    // ω_k = 2 √(k/m) sin((2k − 1)π / (2(2n + 1))) of the uniform shear building
    let w2 = 2.0 * (k / m).sqrt() * (3.0 * std::f64::consts::PI / (2.0 * (2 * n + 1) as f64)).sin();
    let zeta = 0.02;
    let damping = match damping {
        ShearDamping::Modal => format!(r#"{{ "modal": {{ "ratio": {zeta} }} }}"#),
        ShearDamping::Rayleigh => format!(
            r#"{{ "rayleigh": {{ "alpha": {}, "beta": {} }} }}"#,
            2.0 * zeta * w1 * w2 / (w1 + w2),
            2.0 * zeta / (w1 + w2)
        ),
        ShearDamping::Storey => {
            let cs: Vec<String> = (0..n)
                .map(|_| format!("\"{} N*s/m\"", 2.0 * zeta * k / w1))
                .collect();
            format!(r#"{{ "storey": [{}] }}"#, cs.join(", "))
        }
    };
    let masses: Vec<String> = (0..n).map(|_| format!("\"{m} kg\"")).collect();
    let ks: Vec<String> = (0..n).map(|_| format!("\"{k} N/m\"")).collect();
    let hs: Vec<String> = (0..n).map(|_| "\"3.5 m\"".to_string()).collect();
    let ds: Vec<String> = (0..n)
        .map(|i| {
            let above = (n - i) as f64 * m * 9.81;
            format!(
                r#"{{ "floor": {}, "brace_stiffness": "{} N/m", "mass": 0, "brace_damping": 0, "slip_load": "{} N" }}"#,
                i + 1,
                2.0 * k,
                0.05 * above
            )
        })
        .collect();
    format!(
        r#"{{ "name": "shear-{n}", "floor_masses": [{}], "storey_stiffness": [{}], "damping": {damping}, "storey_heights": [{}], "dissipators": [{}] }}"#,
        masses.join(", "),
        ks.join(", "),
        hs.join(", "),
        ds.join(", ")
    )
}
