//! The n-link pendulum, the benchmark of normal modes: its scene (n equal point masses on
//! light links) and the textbook's frequencies, shared by `mechbook bench --links-only` and the
//! tests.

/// The scene of n equal point masses m on light links of length l, each angle from the
/// downward vertical: its Lagrangian, equations, linearisation about hanging at rest, and
/// normal modes at m = 1, l = 1, g = 9.81.
pub fn n_link_scene(n: usize) -> String {
    let q: Vec<String> = (1..=n).map(|i| format!("phi{i}")).collect();
    let mut kinetic = Vec::new();
    for i in 0..n {
        kinetic.push(format!("{}*{}'^2", n - i, q[i]));
        for j in i + 1..n {
            kinetic.push(format!(
                "{}*{}'*{}'*cos({} - {})",
                2 * (n - j),
                q[i],
                q[j],
                q[i],
                q[j]
            ));
        }
    }
    let potential: Vec<String> = (0..n).map(|i| format!("{}*cos({})", n - i, q[i])).collect();
    let coordinates: String = q
        .iter()
        .map(|c| format!("{c} = \"angle of link from the downward vertical\"\n"))
        .collect();
    let about: Vec<String> = q.iter().map(|c| format!("{c} = \"0\"")).collect();
    format!(
        r#"id = "links-{n}"
title = "The {n}-link pendulum"
notes = {{ lecture = "bench" }}
symbols = {{ m = "mass of each bob", l = "length of each link", g = "gravitational acceleration" }}

[coordinates]
{coordinates}
[[step]]
name = "Lag"
be = "m*l^2/2*({}) + m*g*l*({})"
why = "$T - V$"

[[step]]
name = "eom"
lagrange = "Lag"
why = "the Euler–Lagrange equations"

[[step]]
name = "small"
linearise = "eom"
about = {{ {} }}
why = "small angles about hanging at rest"

[[step]]
name = "Omega"
frequency = "small"
why = "the normal modes"

[numeric]
values = {{ m = 1.0, l = 1.0, g = 9.81 }}
"#,
        kinetic.join(" + "),
        potential.join(" + "),
        about.join(", ")
    )
}

/// √λ for the eigenvalues λ of the textbook's M⁻¹K, M_ij = (n − max(i, j)), K = g diag(n, …, 1)
/// (m = l = 1), slowest first: the reference both tools are compared with.
pub fn textbook_modes(n: usize) -> Vec<f64> {
    let m = nalgebra::DMatrix::from_fn(n, n, |i, j| (n - i.max(j)) as f64);
    let k = nalgebra::DMatrix::from_fn(
        n,
        n,
        |i, j| {
            if i == j { 9.81 * (n - i) as f64 } else { 0.0 }
        },
    );
    let a = m.lu().solve(&k).unwrap_or(k);
    let mut out: Vec<f64> = a
        .complex_eigenvalues()
        .iter()
        .map(|l| l.re.sqrt())
        .collect();
    out.sort_by(f64::total_cmp);
    out
}
