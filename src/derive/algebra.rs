//! Scalars, 3-vectors and 3×3 matrices of expressions, and the claim language built on them:
//! `dot`, `cross`, `outer`, `transpose`, `eye()`, `diag`, `rot_x/y/z`, `trace`, products and
//! indexing. Everything here only builds trees; the engine simplifies them.

use crate::cas::{DiffError, Expr};
pub use crate::model::value::{Mat3, Value, Vec3};
use std::collections::BTreeMap;

pub fn zero3() -> Vec3 {
    std::array::from_fn(|_| Expr::int(0))
}

pub fn dot(a: &Vec3, b: &Vec3) -> Expr {
    Expr::add(
        (0..3)
            .map(|i| Expr::mul(vec![a[i].clone(), b[i].clone()]))
            .collect(),
    )
}

pub fn cross(a: &Vec3, b: &Vec3) -> Vec3 {
    let c = |i: usize, j: usize| {
        Expr::minus(
            Expr::mul(vec![a[i].clone(), b[j].clone()]),
            Expr::mul(vec![a[j].clone(), b[i].clone()]),
        )
    };
    [c(1, 2), c(2, 0), c(0, 1)]
}

pub fn scale_vec(s: &Expr, v: &Vec3) -> Vec3 {
    std::array::from_fn(|i| Expr::mul(vec![s.clone(), v[i].clone()]))
}

pub fn add_vec(a: &Vec3, b: &Vec3) -> Vec3 {
    std::array::from_fn(|i| Expr::add(vec![a[i].clone(), b[i].clone()]))
}

/// The sum of many vectors as one sum per entry: adding them two at a time copies the growing
/// sum each time, quadratic in their number (24,000 point masses took 12 minutes).
pub fn sum_vecs(vs: impl IntoIterator<Item = Vec3>) -> Vec3 {
    let mut terms: [Vec<Expr>; 3] = Default::default();
    for v in vs {
        for (t, e) in terms.iter_mut().zip(v) {
            t.push(e);
        }
    }
    terms.map(Expr::add)
}

/// The sum of many matrices, one sum per entry (see [`sum_vecs`]).
pub fn sum_mats(ms: impl IntoIterator<Item = Mat3>) -> Mat3 {
    let mut terms: [[Vec<Expr>; 3]; 3] = Default::default();
    for m in ms {
        for (row, m_row) in terms.iter_mut().zip(m) {
            for (t, e) in row.iter_mut().zip(m_row) {
                t.push(e);
            }
        }
    }
    terms.map(|row| row.map(Expr::add))
}

pub fn sub_vec(a: &Vec3, b: &Vec3) -> Vec3 {
    std::array::from_fn(|i| Expr::minus(a[i].clone(), b[i].clone()))
}

pub fn mat_vec(m: &Mat3, v: &Vec3) -> Vec3 {
    std::array::from_fn(|i| dot(&m[i], v))
}

pub fn mat_mul(a: &Mat3, b: &Mat3) -> Mat3 {
    std::array::from_fn(|i| {
        std::array::from_fn(|j| {
            Expr::add(
                (0..3)
                    .map(|k| Expr::mul(vec![a[i][k].clone(), b[k][j].clone()]))
                    .collect(),
            )
        })
    })
}

pub fn transpose(m: &Mat3) -> Mat3 {
    std::array::from_fn(|i| std::array::from_fn(|j| m[j][i].clone()))
}

pub fn mat_add(a: &Mat3, b: &Mat3) -> Mat3 {
    std::array::from_fn(|i| {
        std::array::from_fn(|j| Expr::add(vec![a[i][j].clone(), b[i][j].clone()]))
    })
}

pub fn mat_scale(s: &Expr, m: &Mat3) -> Mat3 {
    std::array::from_fn(|i| std::array::from_fn(|j| Expr::mul(vec![s.clone(), m[i][j].clone()])))
}

pub fn eye() -> Mat3 {
    diag([Expr::int(1), Expr::int(1), Expr::int(1)])
}

pub fn diag(d: [Expr; 3]) -> Mat3 {
    std::array::from_fn(|i| {
        std::array::from_fn(|j| if i == j { d[i].clone() } else { Expr::int(0) })
    })
}

/// The determinant by cofactors along the first row.
pub fn det(m: &Mat3) -> Expr {
    let minor = |a: &Expr, b: &Expr, c: &Expr, d: &Expr| {
        Expr::minus(
            Expr::mul(vec![a.clone(), b.clone()]),
            Expr::mul(vec![c.clone(), d.clone()]),
        )
    };
    Expr::add(vec![
        Expr::mul(vec![
            m[0][0].clone(),
            minor(&m[1][1], &m[2][2], &m[1][2], &m[2][1]),
        ]),
        Expr::negate(Expr::mul(vec![
            m[0][1].clone(),
            minor(&m[1][0], &m[2][2], &m[1][2], &m[2][0]),
        ])),
        Expr::mul(vec![
            m[0][2].clone(),
            minor(&m[1][0], &m[2][1], &m[1][1], &m[2][0]),
        ]),
    ])
}

/// r²𝟙 − r rᵀ: the inertia-tensor kernel of eq (10) for a unit mass at r.
pub fn inertia_kernel(r: &Vec3) -> Mat3 {
    let r2 = dot(r, r);
    std::array::from_fn(|i| {
        std::array::from_fn(|j| {
            let outer = Expr::mul(vec![r[i].clone(), r[j].clone()]);
            if i == j {
                Expr::minus(r2.clone(), outer)
            } else {
                Expr::negate(outer)
            }
        })
    })
}

/// The right-handed rotation by `angle` about coordinate axis `axis` (0, 1, 2). At a multiple of
/// π/12 its sine and cosine are exact numbers (a body turned by π/2 keeps no cos(π/2)).
pub fn rotation(axis: usize, angle: &Expr) -> Mat3 {
    let c = crate::cas::special_angles(&Expr::call("cos", angle.clone()));
    let s = crate::cas::special_angles(&Expr::call("sin", angle.clone()));
    let (o, z) = (Expr::int(1), Expr::int(0));
    let ns = Expr::negate(s.clone());
    match axis {
        0 => [
            [o, z.clone(), z.clone()],
            [z.clone(), c.clone(), ns],
            [z, s, c],
        ],
        1 => [
            [c.clone(), z.clone(), s],
            [z.clone(), o, z.clone()],
            [ns, z, c],
        ],
        _ => [
            [c.clone(), ns, z.clone()],
            [s, c, z.clone()],
            [z.clone(), z, o],
        ],
    }
}

/// A claim expression that does not make sense: a type error, in words.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ClaimError {
    #[error("cannot add {0} and {1}")]
    Add(&'static str, &'static str),
    #[error("cannot multiply {0} by {1} (use dot, cross or outer)")]
    Multiply(&'static str, &'static str),
    #[error("matrix inverses are not supported in claims")]
    Inverse,
    #[error("cannot raise {0} to {1}")]
    Power(&'static str, &'static str),
    #[error("lists have 3 entries, this one has {0}")]
    ListLength(usize),
    #[error("a list holds three scalars or three rows")]
    ListShape,
    #[error("an index is a literal 0, 1 or 2")]
    Index,
    #[error("cannot index a scalar")]
    IndexScalar,
    #[error("`{name}` cannot take {kinds}")]
    Arguments { name: String, kinds: String },
    #[error(transparent)]
    Diff(#[from] DiffError),
    /// `sign(f)` could not be decided; the reason, in words.
    #[error("{0}")]
    Sign(String),
}

/// The names a claim expression can use, bound to values.
pub type Env = BTreeMap<String, Value>;

/// Evaluates an expression of the claim language to a value. Errors are type errors, in words.
pub fn evaluate(e: &Expr, env: &Env) -> Result<Value, ClaimError> {
    use Value::*;
    Ok(match e {
        Expr::Num(_) => Scalar(e.clone()),
        Expr::Sym(s) => match env.get(s) {
            Some(v) => v.clone(),
            None => Scalar(e.clone()),
        },
        Expr::Add(terms) => {
            let mut acc = evaluate(&terms[0], env)?;
            for t in &terms[1..] {
                acc = match (acc, evaluate(t, env)?) {
                    (Scalar(a), Scalar(b)) => Scalar(Expr::add(vec![a, b])),
                    (Vector(a), Vector(b)) => Vector(add_vec(&a, &b)),
                    (Matrix(a), Matrix(b)) => Matrix(mat_add(&a, &b)),
                    (a, b) => return Err(ClaimError::Add(a.kind(), b.kind())),
                };
            }
            acc
        }
        Expr::Mul(factors) => {
            let mut acc = evaluate(&factors[0], env)?;
            for f in &factors[1..] {
                acc = multiply(acc, evaluate(f, env)?)?;
            }
            acc
        }
        Expr::Pow(b, x) => match (evaluate(b, env)?, evaluate(x, env)?) {
            (Scalar(b), Scalar(x)) => Scalar(Expr::pow(b, x)),
            (Matrix(_), Scalar(Expr::Num(n))) if n.to_i64() == Some(-1) => {
                return Err(ClaimError::Inverse);
            }
            (b, x) => return Err(ClaimError::Power(b.kind(), x.kind())),
        },
        Expr::List(items) => {
            let vals: Vec<Value> = items
                .iter()
                .map(|i| evaluate(i, env))
                .collect::<Result<_, _>>()?;
            if vals.len() != 3 {
                return Err(ClaimError::ListLength(vals.len()));
            }
            match (&vals[0], &vals[1], &vals[2]) {
                (Scalar(a), Scalar(b), Scalar(c)) => Vector([a.clone(), b.clone(), c.clone()]),
                (Vector(a), Vector(b), Vector(c)) => Matrix([a.clone(), b.clone(), c.clone()]),
                _ => return Err(ClaimError::ListShape),
            }
        }
        Expr::Index(a, i) => {
            let Expr::Num(n) = i.as_ref() else {
                return Err(ClaimError::Index);
            };
            let Some(k) = n.to_i64().filter(|k| (0..3).contains(k)) else {
                return Err(ClaimError::Index);
            };
            let k = k as usize;
            match evaluate(a, env)? {
                Vector(v) => Scalar(v[k].clone()),
                Matrix(m) => Vector(m[k].clone()),
                Scalar(_) => return Err(ClaimError::IndexScalar),
            }
        }
        Expr::Call(name, args) => {
            let vals: Vec<Value> = args
                .iter()
                .map(|a| evaluate(a, env))
                .collect::<Result<_, _>>()?;
            call(name, vals)?
        }
    })
}

fn multiply(a: Value, b: Value) -> Result<Value, ClaimError> {
    use Value::*;
    Ok(match (a, b) {
        (Scalar(a), Scalar(b)) => Scalar(Expr::mul(vec![a, b])),
        (Scalar(s), Vector(v)) | (Vector(v), Scalar(s)) => Vector(scale_vec(&s, &v)),
        (Scalar(s), Matrix(m)) | (Matrix(m), Scalar(s)) => Matrix(mat_scale(&s, &m)),
        (Matrix(m), Vector(v)) => Vector(mat_vec(&m, &v)),
        (Matrix(a), Matrix(b)) => Matrix(mat_mul(&a, &b)),
        (a, b) => {
            return Err(ClaimError::Multiply(a.kind(), b.kind()));
        }
    })
}

fn call(name: &str, args: Vec<Value>) -> Result<Value, ClaimError> {
    use Value::*;
    let kinds: Vec<&str> = args.iter().map(|a| a.kind()).collect();
    let bad = || ClaimError::Arguments {
        name: name.to_string(),
        kinds: kinds.join(" and "),
    };
    Ok(match (name, args.as_slice()) {
        (_, [Scalar(x)]) if crate::cas::SCALAR_FUNCTIONS.contains(&name) && name != "atan2" => {
            Scalar(Expr::call(name, x.clone()))
        }
        ("atan2", [Scalar(y), Scalar(x)]) => {
            Scalar(Expr::Call(name.into(), vec![y.clone(), x.clone()]))
        }
        ("dot", [Vector(a), Vector(b)]) => Scalar(dot(a, b)),
        ("cross", [Vector(a), Vector(b)]) => Vector(cross(a, b)),
        ("outer", [Vector(a), Vector(b)]) => Matrix(std::array::from_fn(|i| {
            std::array::from_fn(|j| Expr::mul(vec![a[i].clone(), b[j].clone()]))
        })),
        ("transpose", [Matrix(m)]) => Matrix(transpose(m)),
        ("trace", [Matrix(m)]) => Scalar(Expr::add((0..3).map(|i| m[i][i].clone()).collect())),
        ("det", [Matrix(m)]) => Scalar(det(m)),
        ("eye", []) => Matrix(eye()),
        ("diag", [Scalar(a), Scalar(b), Scalar(c)]) => {
            Matrix(diag([a.clone(), b.clone(), c.clone()]))
        }
        ("diff", [f, Scalar(Expr::Sym(x))]) => {
            let d: Vec<Expr> = f
                .entries()
                .iter()
                .map(|e| e.diff(x))
                .collect::<Result<_, _>>()?;
            f.with_entries(&d)
        }
        // The value of f with the symbol x replaced by v.
        ("subs", [f, Scalar(Expr::Sym(x)), Scalar(v)]) => {
            let e: Vec<Expr> = f
                .entries()
                .iter()
                .map(|e| e.substitute(&|n| (n == x).then(|| v.clone())))
                .collect();
            f.with_entries(&e)
        }
        // 1 or −1 when the sign is the same for all positive values of the symbols, 0 when it
        // is not (see `derive::sign`).
        ("sign", [f]) => {
            let signs = super::sign::signs_over_positive(&f.entries())
                .map_err(|e| ClaimError::Sign(e.to_string()))?;
            let e: Vec<Expr> = signs.iter().map(|s| Expr::int(s.as_int())).collect();
            f.with_entries(&e)
        }
        ("rot_x", [Scalar(a)]) => Matrix(rotation(0, a)),
        ("rot_y", [Scalar(a)]) => Matrix(rotation(1, a)),
        ("rot_z", [Scalar(a)]) => Matrix(rotation(2, a)),
        _ => return Err(bad()),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cas::parse;

    fn ev(s: &str, env: &Env) -> Result<Value, ClaimError> {
        evaluate(&parse(s).unwrap().expr, env)
    }

    fn num(v: &Value) -> Vec<f64> {
        v.entries()
            .iter()
            .map(|e| e.eval(&|_| Some(0.7)).unwrap())
            .collect()
    }

    #[test]
    fn products_and_identities_evaluate() {
        let mut env = Env::new();
        env.insert(
            "u".into(),
            Value::Vector([Expr::int(1), Expr::int(2), Expr::int(3)]),
        );
        env.insert(
            "v".into(),
            Value::Vector([Expr::int(4), Expr::int(5), Expr::int(6)]),
        );
        assert_eq!(
            num(&ev("cross(u, v)", &env).unwrap()),
            vec![-3.0, 6.0, -3.0]
        );
        assert_eq!(num(&ev("dot(u, v)", &env).unwrap()), vec![32.0]);
        assert_eq!(
            num(&ev("diag(1,2,3)*u", &env).unwrap()),
            vec![1.0, 4.0, 9.0]
        );
        assert_eq!(num(&ev("(eye()*2)[1][1]", &env).unwrap()), vec![2.0]);
    }

    #[test]
    fn rotations_are_orthogonal() {
        let env = Env::new();
        for r in ["rot_x(t)", "rot_y(t)", "rot_z(t)"] {
            let q = ev(&format!("transpose({r})*{r}"), &env).unwrap();
            let got = num(&q);
            let want = [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0];
            for (g, w) in got.iter().zip(want) {
                assert!((g - w).abs() < 1e-15, "{r}: {got:?}");
            }
        }
    }

    #[test]
    fn type_errors_are_reported() {
        let mut env = Env::new();
        env.insert(
            "r".into(),
            Value::Vector([Expr::int(1), Expr::int(2), Expr::int(3)]),
        );
        let e = ev("cross(r, dot(r, r))", &env).unwrap_err();
        assert_eq!(
            e,
            ClaimError::Arguments {
                name: "cross".into(),
                kinds: "a vector and a scalar".into()
            }
        );
        assert!(ev("r*r", &env).unwrap_err().to_string().contains("dot"));
        let e = ev("r[3]", &env).unwrap_err();
        assert_eq!(e.to_string(), "an index is a literal 0, 1 or 2");
    }
}
