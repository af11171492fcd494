//! A plot as plain data: `figures` fills it from the numeric results, `render::plot` draws it
//! as SVG. Keeping the numbers here (not in the renderer) lets tests check a plot's content
//! without parsing SVG.

#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum Mark {
    /// A polyline through the points.
    Line,
    /// A dashed polyline: a predicted law, not a measurement.
    Dashed,
    /// Separate markers: sampled or measured values.
    Points,
}

#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Series {
    pub name: String,
    pub mark: Mark,
    /// Index into the renderer's palette, so that a law and its measurement share a colour.
    pub colour: usize,
    pub points: Vec<(f64, f64)>,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum Scale {
    Linear,
    Log,
}

/// Where the legend goes: a corner or edge the data leave empty.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum Legend {
    UpperRight,
    UpperLeft,
    MiddleRight,
    LowerRight,
    LowerLeft,
}

/// What one numeric result behind a figure reached, and what it cost, at the build's fidelity.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Accuracy {
    /// The result, and the method and setting that computed it.
    pub result: String,
    pub method: String,
    /// Relative error against an exact value, where one exists.
    pub true_error: Option<f64>,
    /// What the method can tell without an exact value: its tolerance-driven estimate or the
    /// drift of the invariants 2T and |L| it should conserve.
    pub estimated_error: Option<f64>,
    /// Work done, counted in `unit`s (deterministic, unlike seconds).
    pub cost: u64,
    pub unit: String,
    pub seconds: f64,
}

#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Figure {
    /// Unique within the scene; the file is `plots/<scene>-<slug>.svg`.
    pub slug: String,
    pub title: String,
    /// A sentence or two written from the data: the caption, and in plain text `<desc>` and the
    /// alt text. Its symbols are formulas, set as the page sets them (I_xx as I with xx below).
    pub desc: crate::model::prose::Prose,
    pub x_label: String,
    pub y_label: String,
    pub x_scale: Scale,
    pub y_scale: Scale,
    /// A projected 3-D view: equal units on both axes and no axis ticks.
    pub equal_aspect: bool,
    pub series: Vec<Series>,
    /// Text placed at data coordinates, such as the names of projected axes.
    pub labels: Vec<(String, (f64, f64))>,
    pub legend: Legend,
    /// The error and cost of each numeric result drawn.
    pub accuracy: Vec<Accuracy>,
}

impl Figure {
    /// The smallest and largest x and y over every series, ignoring values a log axis cannot show.
    pub fn bounds(&self) -> Option<((f64, f64), (f64, f64))> {
        let ok = |v: f64, s: Scale| v.is_finite() && (s == Scale::Linear || v > 0.0);
        let mut it = self
            .series
            .iter()
            .flat_map(|s| s.points.iter())
            .filter(|(x, y)| ok(*x, self.x_scale) && ok(*y, self.y_scale));
        let (x0, y0) = *it.next()?;
        Some(it.fold(((x0, x0), (y0, y0)), |((a, b), (c, d)), (x, y)| {
            ((a.min(*x), b.max(*x)), (c.min(*y), d.max(*y)))
        }))
    }
}
