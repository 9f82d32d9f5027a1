//! The neutral sketch: what the three readers produce and the lowering turns into a gcs model.
//!
//! It speaks the CAD programs' vocabulary (arcs with their end points, constraints on a curve's
//! centre or end point, equal radius or equal length, symmetric about a line or a point,
//! horizontal distance, a line's angle against the axes, external geometry) so that each reader
//! only *translates* its format, and one lowering ([`crate::lower`]) decides how the vocabulary
//! becomes gcs entities and constraints. What a reader cannot express here goes to
//! [`Sketch::skipped`] with its reason: nothing is dropped silently.
//!
//! Conventions every reader follows:
//! - **Units**: lengths in millimetres (Onshape's metres are multiplied by 1000), angles in
//!   degrees (FreeCAD's radians converted).
//! - **Numbers** are exact rationals ([`Number`]): a decimal written in the file is read as the
//!   rational it denotes; a float computed by the reader (a FreeCAD arc's end point from its
//!   angles) is taken as the shortest decimal that round-trips.
//! - **Ids** are the source's own names, so that a report can be traced back: FreeCAD's
//!   `Edge3` / `Constraint7`, SolveSpace's handles (`e.0002000a`, `c.00000007`), Onshape's
//!   entity and constraint ids. They are unique within a sketch (a reader makes them so, for
//!   instance by prefixing, and says how in its module documentation).
//! - **Positions** are the drawing as the file stores it (the CAD program's last solution).

use num_rational::BigRational;

/// An exact number (see the module documentation).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Number(pub BigRational);

impl Number {
    /// Parses a decimal (`-12`, `3.1623`, `1.5e-3`) or a fraction (`2/3`) exactly; `None` for
    /// anything else (including `inf`, `nan`).
    pub fn parse(text: &str) -> Option<Number> {
        gcs_model::number::parse_exact(text).map(Number)
    }

    /// The shortest decimal that round-trips to `x`; `None` for infinities and NaN.
    pub fn from_f64(x: f64) -> Option<Number> {
        gcs_model::number::rational_from_f64_decimal(x).map(Number)
    }

    /// An integer.
    pub fn from_i64(x: i64) -> Number {
        Number(BigRational::from_integer(x.into()))
    }

    /// The nearest `f64`.
    pub fn to_f64(&self) -> f64 {
        num_traits::ToPrimitive::to_f64(&self.0).unwrap_or(f64::NAN)
    }
}

/// A position: 2 coordinates in a 2D sketch, 3 in 3D.
pub type Coords = Vec<Number>;

/// One sketch of a file: one model.
#[derive(Clone, Debug, PartialEq)]
pub struct Sketch {
    /// The model name (normative, see `docs/format.md`): `"<file stem>/<sketch>"` — FreeCAD:
    /// the sketch object's `Name` (`Bielle/Sketch005`); SolveSpace: `g<group handle in
    /// decimal>` (`normal/g2`); Onshape JSON: the sketch's index among the file's sketch
    /// features (`…_featurescript_004/0`).
    pub name: String,
    /// A human label when the source has one beside the name (FreeCAD's `Label`, Onshape's
    /// feature name, SolveSpace's group name).
    pub label: Option<String>,
    /// 2 for a planar sketch, 3 for a 3D one (SolveSpace groups not in a workplane).
    pub dim: u8,
    /// The entities, in the source's order.
    pub entities: Vec<Entity>,
    /// The constraints, in the source's order.
    pub constraints: Vec<Constraint>,
    /// What could not be expressed, each with its reason.
    pub skipped: Vec<Skipped>,
    /// What was not imported although nothing is lost, each with why: an item said by another
    /// (SolveSpace's coincidence at a tangent joint, folded into `TangentAtEnds`), an
    /// annotation that is not geometry (a comment).
    pub notes: Vec<Skipped>,
    /// What the source program recorded about its own solution, when it does (for example a
    /// DOF count or a "fully constrained" flag), as `(name, value)` pairs, verbatim.
    pub source_verdict: Vec<(String, String)>,
}

impl Sketch {
    /// An empty planar sketch, for a reader to fill.
    pub(crate) fn planar(name: String, label: Option<String>) -> Sketch {
        Sketch {
            name,
            label,
            dim: 2,
            entities: Vec::new(),
            constraints: Vec::new(),
            skipped: Vec::new(),
            notes: Vec::new(),
            source_verdict: Vec::new(),
        }
    }
}

/// An item a reader could not express, and why.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Skipped {
    /// The source's id of the item (an entity, a constraint, a feature).
    pub item: String,
    /// Why: what kind of item it is and what is missing (`"B-spline knot vector of degree 0"`,
    /// `"constraint type 19 (Weight) is not supported"`).
    pub reason: String,
}

/// One entity.
#[derive(Clone, Debug, PartialEq)]
pub struct Entity {
    /// The source's id (see the module documentation).
    pub id: String,
    /// Its shape and drawing.
    pub geometry: Geometry,
    /// Construction geometry (drawn dashed in the CAD program): analysed like any other.
    pub construction: bool,
    /// External geometry (a projection of a model edge, a reference to another sketch, the
    /// sketch's axes and origin): fixed where it is drawn.
    pub external: bool,
}

/// An entity's shape, with its drawing. Each kind has named points ([`Part`]) that constraints
/// can address.
#[derive(Clone, Debug, PartialEq)]
pub enum Geometry {
    /// A point. Parts: none (address it with [`Part::Whole`]).
    Point {
        /// Position.
        at: Coords,
    },
    /// A line segment. Parts: [`Part::Start`], [`Part::End`]. Its length may be zero in the
    /// drawing (a reader turns a zero-length line into a point when the source means one).
    Segment {
        /// Start point.
        start: Coords,
        /// End point.
        end: Coords,
    },
    /// An infinite line through two distinct points (SolveSpace's workplane axes, FreeCAD's
    /// H and V axes, construction lines that CAD programs call infinite). Parts: none.
    Line {
        /// A point on it.
        a: Coords,
        /// Another point on it.
        b: Coords,
    },
    /// A circle. Parts: [`Part::Center`].
    Circle {
        /// Centre.
        center: Coords,
        /// Radius (> 0).
        radius: Number,
    },
    /// A circular arc, counter-clockwise from `start` to `end` about `center` (a reader whose
    /// source runs clockwise swaps them and says so). Parts: [`Part::Center`], [`Part::Start`],
    /// [`Part::End`]. Its radius is the distance from the centre to the start point.
    Arc {
        /// Centre.
        center: Coords,
        /// Start point.
        start: Coords,
        /// End point.
        end: Coords,
    },
    /// An ellipse. Parts: [`Part::Center`], [`Part::Focus1`], [`Part::Focus2`],
    /// [`Part::MajorStart`]/[`Part::MajorEnd`]/[`Part::MinorStart`]/[`Part::MinorEnd`] (the
    /// ends of its axes).
    Ellipse {
        /// Centre.
        center: Coords,
        /// The end of the major axis on its positive side: `center + major_radius · u`.
        major: Coords,
        /// The minor radius (≤ the major radius).
        minor_radius: Number,
    },
    /// An arc of an ellipse, counter-clockwise from parameter `start` to `end` (radians, the
    /// eccentric anomaly from the major axis). Parts: those of [`Geometry::Ellipse`] and
    /// [`Part::Start`], [`Part::End`].
    EllipticalArc {
        /// Centre.
        center: Coords,
        /// The end of the major axis (as for the ellipse).
        major: Coords,
        /// The minor radius.
        minor_radius: Number,
        /// The start point, on the ellipse.
        start: Coords,
        /// The end point, on the ellipse.
        end: Coords,
    },
    /// A B-spline (NURBS when `weights` is given). Parts: [`Part::Pole`]`(i)` for each control
    /// point, [`Part::Start`] and [`Part::End`] (the curve's end points: the first and last
    /// poles of a clamped open spline).
    BSpline {
        /// Degree (≥ 1).
        degree: u32,
        /// Control points.
        poles: Vec<Coords>,
        /// Weights, one per pole (`None`: all 1).
        weights: Option<Vec<Number>>,
        /// Knots with their multiplicities, as `(knot, multiplicity)`.
        knots: Vec<(Number, u32)>,
        /// Periodic (closed) or open.
        periodic: bool,
    },
    /// A plane in a 3D sketch (a SolveSpace workplane). Parts: [`Part::Origin`].
    Plane {
        /// A point on it.
        origin: Coords,
        /// Its normal (not zero).
        normal: Coords,
    },
}

/// A named point of an entity (or the entity itself).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Part {
    /// The entity itself.
    Whole,
    /// Start point (segment, arc, elliptical arc, spline).
    Start,
    /// End point (segment, arc, elliptical arc, spline).
    End,
    /// Centre (circle, arc, ellipse, elliptical arc).
    Center,
    /// First focus of an ellipse (on the positive side of the major axis).
    Focus1,
    /// Second focus.
    Focus2,
    /// Ends of an ellipse's axes.
    MajorStart,
    /// See [`Part::MajorStart`].
    MajorEnd,
    /// See [`Part::MajorStart`].
    MinorStart,
    /// See [`Part::MajorStart`].
    MinorEnd,
    /// Control point `i` of a spline (0-based).
    Pole(usize),
    /// A plane's origin point.
    Origin,
    /// The tangent handle at a clamped spline's start: the first leg of its control polygon
    /// (a segment from its start to its second control point), which gives the curve's
    /// direction there (Onshape's `startDerivative`).
    StartTangent,
    /// The tangent handle at a clamped spline's end: the last leg of its control polygon.
    EndTangent,
}

/// A reference from a constraint to an entity or one of its named points.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct Ref {
    /// The entity's id.
    pub entity: String,
    /// Which part of it.
    pub part: Part,
}

impl Ref {
    /// The entity itself.
    pub fn whole(entity: impl Into<String>) -> Ref {
        Ref { entity: entity.into(), part: Part::Whole }
    }

    /// A named point of the entity.
    pub fn part(entity: impl Into<String>, part: Part) -> Ref {
        Ref { entity: entity.into(), part }
    }
}

/// One constraint.
#[derive(Clone, Debug, PartialEq)]
pub struct Constraint {
    /// The source's id (see the module documentation).
    pub id: String,
    /// What it says, with its references in the order the kind documents.
    pub kind: Kind,
    /// The references.
    pub refs: Vec<Ref>,
    /// The dimension (mm or degrees), for the kinds that have one.
    pub value: Option<Number>,
    /// `false` for a reference (driven, non-driving) dimension: measured, not imposed.
    pub driving: bool,
}

/// What a constraint says. The references, in order, are given for each kind; "point" means a
/// reference to a point entity or to a named point of a curve, "curve" a segment, line, circle,
/// arc, ellipse, elliptical arc or spline.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Kind {
    /// `[point, point]`: the two points coincide.
    Coincident,
    /// `[point, curve]`: the point lies on the curve (on a segment's or arc's carrier: the
    /// infinite line, the full circle).
    PointOnObject,
    /// `[segment or line]` (horizontal), or `[point, point]` (the two points level).
    Horizontal,
    /// `[segment or line]`, or `[point, point]`.
    Vertical,
    /// `[line, line]`.
    Parallel,
    /// `[line, line]`.
    Perpendicular,
    /// `[curve, curve]`: tangent somewhere (no shared point given).
    Tangent,
    /// `[curve end point, curve end point]` (refs with parts `Start`/`End`): the two curves
    /// meet at these end points and are tangent there (a fillet's joint; FreeCAD's
    /// endpoint-to-endpoint tangency). One constraint, not coincidence + tangency.
    TangentAtEnds,
    /// `[curve end point, curve end point]`: the curves meet at these end points at a right
    /// angle.
    PerpendicularAtEnds,
    /// `[curve, curve]`: equal length (two segments) or equal radius (two circles or arcs).
    Equal,
    /// `[point, point, point or line]`: the first two are symmetric about the third;
    /// `[segment, segment, point or line]`: the carriers (infinite lines) of the first two are
    /// symmetric about the third (a mirrored line).
    Symmetric,
    /// `[point, point]`, `[point, line]`, `[point, circle]` (to its boundary), `[line, line]`
    /// (parallel lines), `[circle, circle]` (between boundaries): `value` apart.
    Distance,
    /// `[segment]`: its length is `value`.
    Length,
    /// `[point, point]` (or `[segment]`, its end points): `value` is the second point's x
    /// minus the first's.
    DistanceX,
    /// `[point, point]` (or `[segment]`): `value` is the second point's y minus the first's.
    DistanceY,
    /// `[line, line]`: the angle from the first to the second is `value` degrees.
    Angle,
    /// `[line]`: the angle of the line against the x axis is `value` degrees.
    AngleToXAxis,
    /// `[circle or arc]`.
    Radius,
    /// `[circle or arc]`.
    Diameter,
    /// `[entity]`: fixed where it is drawn (FreeCAD's Block, Onshape's FIX).
    Fix,
    /// `[point, segment or arc]`: the point is the midpoint.
    Midpoint,
    /// `[circle or arc, circle or arc]`: same centre.
    Concentric,
    /// `[line, line]`: on one line.
    Collinear,
    /// `[line, line, line, line]`: the angle between the first two equals the angle between
    /// the last two (SolveSpace's EQUAL_ANGLE).
    EqualAngle,
    /// `[segment, segment]`: the first's length over the second's is `value`.
    LengthRatio,
    /// `[segment, segment]`: the first's length minus the second's is `value`.
    LengthDifference,
    /// `[segment, arc]`: the segment is as long as the arc.
    EqualLineArcLength,
    /// `[point, line, point, line]`: the distance from the first point to the first line equals
    /// the distance from the second point to the second line.
    EqualPointLineDistances,
    /// `[a, b, c, d]`: the gap between `a` and `b` equals the gap between `c` and `d`, each
    /// pair two circles or arcs (the difference of their radii, up to sign: the gap of
    /// concentric ones), a point and a line, or two points (equal offsets of curves).
    EqualGaps,
    /// `[segment, point, line]`: the segment's length equals the distance from the point to the
    /// line.
    EqualLengthPointLineDistance,
    /// `[arc or circle]`: its arc length (an arc) or circumference is `value`.
    ArcLength,
    /// `[point, point, point]`: the second is the first turned by `value` degrees,
    /// counter-clockwise, about the third (an instance of a circular pattern).
    Rotated,
    /// `[point, point, point, point]`: the second minus the first equals the fourth minus the
    /// third (an instance of a linear pattern, one step along a direction segment from its
    /// start to its end).
    Translated,
    /// `[point, spline]`: the point is the spline's point at the parameter `value`, one of its
    /// knots (an interpolation point of a spline drawn through points).
    SplinePoint,
}
