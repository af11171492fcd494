//! The value of a derived quantity: a scalar, a 3-vector or a 3×3 matrix of exact expressions,
//! and its one evaluation at a scene's numeric values.

use crate::cas::{EvalError, Expr};
use nalgebra::{Matrix3, Vector3};
use std::collections::BTreeMap;

/// A scene's `[numeric] values`: symbol -> number.
pub type Values = BTreeMap<String, f64>;

/// An expression at the scene's values (π is known without a value).
pub fn eval_at(e: &Expr, values: &Values) -> Result<f64, EvalError> {
    e.eval(&|s| values.get(s).copied())
}

pub type Vec3 = [Expr; 3];
pub type Mat3 = [[Expr; 3]; 3];

// A matrix is nine times a scalar; values are few and short-lived, so boxing buys nothing.
#[allow(clippy::large_enum_variant)]
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub enum Value {
    Scalar(Expr),
    Vector(Vec3),
    Matrix(Mat3),
}

impl Value {
    /// Its kind, as the catalogue names it.
    pub fn kind_of(&self) -> crate::model::catalogue::Kind {
        use crate::model::catalogue::Kind;
        match self {
            Value::Scalar(_) => Kind::Scalar,
            Value::Vector(_) => Kind::Vector,
            Value::Matrix(_) => Kind::Matrix,
        }
    }

    pub fn kind(&self) -> &'static str {
        match self {
            Value::Scalar(_) => "a scalar",
            Value::Vector(_) => "a vector",
            Value::Matrix(_) => "a matrix",
        }
    }

    /// The entries in row-major order.
    pub fn entries(&self) -> Vec<Expr> {
        match self {
            Value::Scalar(e) => vec![e.clone()],
            Value::Vector(v) => v.to_vec(),
            Value::Matrix(m) => m.iter().flatten().cloned().collect(),
        }
    }

    /// Rebuilds a value of the same shape from row-major entries.
    pub fn with_entries(&self, entries: &[Expr]) -> Value {
        match self {
            Value::Scalar(_) => Value::Scalar(entries[0].clone()),
            Value::Vector(_) => Value::Vector(std::array::from_fn(|i| entries[i].clone())),
            Value::Matrix(_) => Value::Matrix(std::array::from_fn(|i| {
                std::array::from_fn(|j| entries[3 * i + j].clone())
            })),
        }
    }

    /// Where entry `k` sits, for messages: `""`, `[1]` or `[0][2]`.
    pub fn entry_label(&self, k: usize) -> String {
        match self {
            Value::Scalar(_) => String::new(),
            Value::Vector(_) => format!("[{k}]"),
            Value::Matrix(_) => format!("[{}][{}]", k / 3, k % 3),
        }
    }

    /// As an expression in the claim language (lists for vectors and matrices).
    pub fn to_expr(&self) -> Expr {
        match self {
            Value::Scalar(e) => e.clone(),
            Value::Vector(v) => Expr::List(v.to_vec()),
            Value::Matrix(m) => Expr::List(m.iter().map(|r| Expr::List(r.to_vec())).collect()),
        }
    }

    pub fn to_text(&self) -> String {
        self.to_expr().to_text()
    }

    /// The value as the tree the pages set.
    pub fn to_tex(&self, names: &crate::notation::Names) -> crate::notation::Tex {
        self.to_expr().to_tex(names)
    }
}

impl Value {
    /// Every entry at the scene's values, in row-major order.
    pub fn numbers_at(&self, values: &Values) -> Result<Vec<f64>, EvalError> {
        self.entries().iter().map(|e| eval_at(e, values)).collect()
    }

    /// A matrix value at the scene's values.
    pub fn matrix_at(&self, values: &Values) -> Result<Matrix3<f64>, EvalError> {
        match self {
            Value::Matrix(_) => Ok(Matrix3::from_row_slice(&self.numbers_at(values)?)),
            _ => Err(EvalError::Shape {
                expected: "a matrix",
                found: self.kind(),
            }),
        }
    }
}

/// A vector of expressions at the scene's values.
pub fn vector_at(v: &Vec3, values: &Values) -> Result<Vector3<f64>, EvalError> {
    Ok(Vector3::new(
        eval_at(&v[0], values)?,
        eval_at(&v[1], values)?,
        eval_at(&v[2], values)?,
    ))
}
