//! A body with numbers in place of symbols, and the inertia tensor of a weighted point set.
//! This code shares no formula with the symbolic route: only the scene's geometry.

use crate::cas::EvalError;
use crate::model::value::{Values, eval_at, vector_at};
use crate::scene::{Body, ConeOrigin, Shape};
use nalgebra::{Matrix3, Rotation3, Vector2, Vector3};

#[derive(Debug, Clone)]
pub enum NumShape {
    Box {
        size: Vector3<f64>,
        centred: bool,
    },
    Rod {
        length: f64,
        along: usize,
        centred: bool,
    },
    Plate {
        size: Vector2<f64>,
        centred: bool,
    },
    Hoop {
        radius: f64,
    },
    /// `inner` is 0 for a full disk, cylinder or ball.
    Disk {
        radius: f64,
        inner: f64,
    },
    Cylinder {
        radius: f64,
        height: f64,
        inner: f64,
    },
    Sphere {
        radius: f64,
        inner: f64,
    },
    /// The apex at z = `apex`; the base at z = apex + `direction`·h.
    Cone {
        radius: f64,
        height: f64,
        apex: f64,
        direction: f64,
    },
    /// The dome towards +z; the flat face at z = `face`.
    Hemisphere {
        radius: f64,
        face: f64,
    },
    Shell {
        radius: f64,
    },
    Points(Vec<(f64, Vector3<f64>)>),
}

#[derive(Debug, Clone)]
pub struct NumBody {
    pub label: String,
    pub shape: NumShape,
    pub mass: f64,
    /// Body -> frame: x_frame = rotation · x_body + shift.
    pub rotation: Matrix3<f64>,
    pub shift: Vector3<f64>,
}

impl NumBody {
    /// Evaluates a scene body at the scene's values.
    pub fn from_scene(body: &Body, values: &Values) -> Result<NumBody, EvalError> {
        let ev = |e: &crate::cas::Expr| eval_at(e, values);
        let v3 = |v: &[crate::cas::Expr; 3]| vector_at(v, values);
        let inner_at = |i: &Option<crate::cas::Expr>| i.as_ref().map_or(Ok(0.0), ev);
        let shape = match &body.shape {
            Shape::Box { size, centred } => NumShape::Box {
                size: v3(size)?,
                centred: *centred,
            },
            Shape::Rod {
                length,
                along,
                centred,
            } => NumShape::Rod {
                length: ev(length)?,
                along: along.index(),
                centred: *centred,
            },
            Shape::Plate { size, centred } => NumShape::Plate {
                size: Vector2::new(ev(&size[0])?, ev(&size[1])?),
                centred: *centred,
            },
            Shape::Hoop { radius } => NumShape::Hoop {
                radius: ev(radius)?,
            },
            Shape::Disk { radius, inner } => NumShape::Disk {
                radius: ev(radius)?,
                inner: inner_at(inner)?,
            },
            Shape::Cylinder {
                radius,
                height,
                inner,
            } => NumShape::Cylinder {
                radius: ev(radius)?,
                height: ev(height)?,
                inner: inner_at(inner)?,
            },
            Shape::Sphere { radius, inner } => NumShape::Sphere {
                radius: ev(radius)?,
                inner: inner_at(inner)?,
            },
            Shape::Cone {
                radius,
                height,
                origin,
            } => {
                let h = ev(height)?;
                cone(ev(radius)?, h, origin)
            }
            Shape::Hemisphere { radius, centred } => {
                let r = ev(radius)?;
                NumShape::Hemisphere {
                    radius: r,
                    face: if *centred { -0.375 * r } else { 0.0 },
                }
            }
            Shape::Shell { radius } => NumShape::Shell {
                radius: ev(radius)?,
            },
            Shape::Points(pts) => NumShape::Points(
                pts.iter()
                    .map(|(m, at)| Ok((ev(m)?, v3(at)?)))
                    .collect::<Result<_, EvalError>>()?,
            ),
        };
        let mut rotation = Matrix3::identity();
        for (axis, angle) in &body.rotations {
            let unit = nalgebra::Unit::new_unchecked(Vector3::ith(axis.index(), 1.0));
            rotation = Rotation3::from_axis_angle(&unit, ev(angle)?).into_inner() * rotation;
        }
        Ok(NumBody {
            label: body.label.clone(),
            shape,
            mass: ev(&body.mass)?,
            rotation,
            shift: v3(&body.shift)?,
        })
    }

    /// Maps a body-frame point into the scene frame.
    pub fn place(&self, local: &Vector3<f64>) -> Vector3<f64> {
        self.rotation * local + self.shift
    }
}

/// I = Σ w (r² 𝟙 − r rᵀ) over weighted points in the scene frame, eq (10) as a sum.
///
/// A unit mass on the x axis at distance 2 has no moment about x and 4 about y and z:
///
/// ```
/// use nalgebra::Vector3;
/// let t = mechbook::numeric::body::tensor_of_points([(1.0, Vector3::new(2.0, 0.0, 0.0))].into_iter());
/// assert_eq!((t[(0, 0)], t[(1, 1)], t[(2, 2)]), (0.0, 4.0, 4.0));
/// ```
pub fn tensor_of_points(points: impl Iterator<Item = (f64, Vector3<f64>)>) -> Matrix3<f64> {
    let mut t = Matrix3::zeros();
    for (w, r) in points {
        t += w * (Matrix3::identity() * r.norm_squared() - r * r.transpose());
    }
    t
}

/// Relative max-norm distance between two tensors, scaled by the larger entry of `exact`.
pub fn relative_error(approx: &Matrix3<f64>, exact: &Matrix3<f64>) -> f64 {
    crate::base::float::max_relative_error(approx.as_slice(), exact.as_slice())
}

/// A cone of `radius` and height `h` whose frame's origin is its apex, its base or its centre
/// of mass (a quarter of the height up from the base): its apex's height and the direction of
/// its axis from there.
fn cone(radius: f64, h: f64, origin: &ConeOrigin) -> NumShape {
    let (apex, direction) = match origin {
        ConeOrigin::Apex => (0.0, 1.0),
        ConeOrigin::Base => (h, -1.0),
        ConeOrigin::Centre => (0.75 * h, -1.0),
    };
    NumShape::Cone {
        radius,
        height: h,
        apex,
        direction,
    }
}
