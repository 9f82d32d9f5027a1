//! Pictures of an analysis (`gcs analyze --svg DIR`): the sketch drawn as SVG, each rigid
//! cluster in its own colour, the redundant constraints in orange (consistent at the values, or
//! not measured) or red (conflicting), the constraints dependent only at this drawing (a
//! singular position) in magenta, each with what it depends on in its tooltip (`<title>`), and
//! the verdict written above the drawing.
//!
//! Everything drawn comes from the model (the entities at their sketch positions) and from the
//! [`Report`] (clusters, redundancy, the singular-configuration section): the picture says what
//! the JSON report says; and the drawing's free motions (where its degrees of freedom are) as
//! grey arrows, computed exactly at the drawing ([`gcs_analysis::motions`]). 3D models are drawn projected onto the xy plane, as the title says.

use gcs_model::entity::Geometry;
use gcs_model::{EntityIdx, System};
use num_traits::ToPrimitive;
use svg::Document;
use svg::node::element::{Circle, Group, Line, Path, Text, Title};

use crate::Report;

/// The colours of the clusters, in order (then again).
const PALETTE: [&str; 8] =
    ["#1f77b4", "#2ca02c", "#9467bd", "#8c564b", "#17becf", "#bcbd22", "#e377c2", "#7f7f7f"];
/// Entities in no cluster.
const LOOSE: &str = "#555555";
const REDUNDANT: &str = "#ff7f0e";
const CONFLICTING: &str = "#d62728";
const SINGULAR: &str = "#c800c8";
const MOTION: &str = "#444444";

/// A 2D position of the drawing (y up, as in the model).
type P = [f64; 2];

fn f(q: &gcs_model::BigRational) -> f64 {
    q.to_f64().unwrap_or(f64::NAN)
}

fn xy(c: &[gcs_model::BigRational]) -> Option<P> {
    Some([f(c.first()?), f(c.get(1)?)])
}

/// Where an entity is drawn: a point's position, a circle's or arc's centre, the middle of a
/// segment or of a line's two sketch points.
fn anchor(system: &System, e: EntityIdx) -> Option<P> {
    match &system.entity(e).geometry {
        Geometry::Point { at } => xy(at.as_ref()?),
        Geometry::Circle { center, .. }
        | Geometry::Sphere { center, .. }
        | Geometry::Arc { center, .. } => xy(center.as_ref()?),
        Geometry::Segment { from, to } => {
            let (a, b) = (anchor(system, *from)?, anchor(system, *to)?);
            Some([(a[0] + b[0]) / 2.0, (a[1] + b[1]) / 2.0])
        }
        Geometry::Line { at } | Geometry::Plane { at } => {
            let [p, _] = at.as_ref()?;
            xy(p)
        }
        // Its middle control point.
        Geometry::BSpline { poles, .. } => anchor(system, *poles.get(poles.len() / 2)?),
    }
}

/// Points along a B-spline at its control points' sketch positions (`None` when one has
/// none), for drawing it as a polyline.
fn spline_points(system: &System, e: EntityIdx) -> Option<Vec<P>> {
    let Geometry::BSpline { degree, poles, knots, weights, periodic } = &system.entity(e).geometry
    else {
        return None;
    };
    let at: Option<Vec<Vec<f64>>> = poles
        .iter()
        .map(|p| match &system.entity(*p).geometry {
            Geometry::Point { at } => at.as_ref().map(|c| c.iter().map(f).collect()),
            _ => None,
        })
        .collect();
    let k = gcs_model::spline::knots_or_default(*degree, poles.len(), knots.as_deref(), *periodic);
    let w = weights.as_deref().unwrap_or_default();
    let curve = gcs_model::spline::sample(*degree, &at?, &k, w, *periodic, 16 * poles.len());
    let curve: Vec<P> = curve.iter().filter_map(|c| Some([*c.first()?, *c.get(1)?])).collect();
    (!curve.is_empty()).then_some(curve)
}

/// The drawing's extent: every anchor, and circles and arcs in full.
fn bounds(system: &System) -> Option<(P, P)> {
    let mut lo = [f64::INFINITY; 2];
    let mut hi = [f64::NEG_INFINITY; 2];
    let mut add = |p: P, r: f64| {
        for k in 0..2 {
            lo[k] = lo[k].min(p[k] - r);
            hi[k] = hi[k].max(p[k] + r);
        }
    };
    for e in system.entity_indices() {
        let Some(p) = anchor(system, e) else { continue };
        let r = match &system.entity(e).geometry {
            Geometry::Circle { radius, .. }
            | Geometry::Sphere { radius, .. }
            | Geometry::Arc { radius, .. } => radius.as_ref().map_or(0.0, |r| f(r).abs()),
            Geometry::Line { at: Some([_, q]) } => {
                if let Some(q) = xy(q) {
                    add(q, 0.0);
                }
                0.0
            }
            _ => 0.0,
        };
        if p[0].is_finite() && p[1].is_finite() && r.is_finite() {
            add(p, r);
        }
    }
    (lo[0] <= hi[0] && lo[1] <= hi[1]).then_some((lo, hi))
}

/// The most unknowns for which [`analysis_svg`] computes the free motions (exactly, at the
/// drawing).
pub const MOTIONS_LIMIT: usize = 600;

/// The SVG of `report` (an analysis of `system`), as text, with the drawing's free motions
/// when the drawing satisfies its constraints and the system has at most [`MOTIONS_LIMIT`]
/// unknowns.
pub fn analysis_svg(system: &System, report: &Report) -> String {
    let satisfied = report.sketch.as_ref().is_none_or(|s| s.satisfied);
    let motions =
        if satisfied && report.dof + report.sketch.as_ref().map_or(0, |s| s.extra_motions) > 0 {
            gcs_analysis::motions::free_motions(system, MOTIONS_LIMIT).unwrap_or_default()
        } else {
            Vec::new()
        };
    analysis_svg_with_motions(system, report, &motions)
}

/// [`analysis_svg`] with the drawing's free motions
/// ([`gcs_analysis::motions::free_motions`]: velocities over the columns of the system's
/// layout) drawn as grey arrows at the points they move, one set per motion, each scaled so
/// that its longest arrow is 7% of the drawing's size (within its margin).
pub fn analysis_svg_with_motions(system: &System, report: &Report, motions: &[Vec<f64>]) -> String {
    let Some((lo, hi)) = bounds(system) else {
        return Document::new().add(Text::new("nothing drawn: no sketch positions")).to_string();
    };
    let size = (hi[0] - lo[0]).max(hi[1] - lo[1]).max(1e-9);
    let margin = 0.08 * size;
    // Model y goes up; SVG's down: y is negated.
    let (x0, y0) = (lo[0] - margin, -hi[1] - margin);
    let (w, h) = (hi[0] - lo[0] + 2.0 * margin, hi[1] - lo[1] + 2.0 * margin);
    // At least as wide as tall, the drawing centred: the caption's lines are as long as a
    // square's side.
    let (x0, w) = if w < h { (x0 - 0.5 * (h - w), h) } else { (x0, w) };
    let head = 0.2 * w.max(h);
    let dot = 0.009 * size;
    let font = 0.024 * w.max(h);
    let line_width = 0.004 * size;

    let colour_of = |e: &str| -> &'static str {
        report
            .clusters
            .iter()
            .position(|c| c.entities.iter().any(|x| x == e))
            .map_or(LOOSE, |k| PALETTE[k % PALETTE.len()])
    };
    let at = |p: P| (p[0], -p[1]);

    let mut shapes = Group::new().set("fill", "none").set("stroke-linecap", "round");
    for e in system.entity_indices() {
        let entity = system.entity(e);
        let colour = colour_of(&entity.id);
        let title = Title::new(format!("{} ({})", entity.id, entity.kind().name()));
        let shape: Option<svg::node::element::Element> = match &entity.geometry {
            Geometry::Point { .. } => anchor(system, e).map(|p| {
                let (cx, cy) = at(p);
                Circle::new()
                    .set("cx", cx)
                    .set("cy", cy)
                    .set("r", dot)
                    .set("fill", colour)
                    .set("stroke", "none")
                    .add(title)
                    .into()
            }),
            Geometry::Segment { from, to } => {
                anchor(system, *from).zip(anchor(system, *to)).map(|(a, b)| {
                    let ((x1, y1), (x2, y2)) = (at(a), at(b));
                    segment(x1, y1, x2, y2, colour, line_width).add(title).into()
                })
            }
            Geometry::Line { at: Some([p, q]) } | Geometry::Plane { at: Some([p, q]) }
                if matches!(entity.geometry, Geometry::Line { .. }) =>
            {
                xy(p).zip(xy(q)).map(|(a, b)| {
                    // Extended across the drawing.
                    let d = [b[0] - a[0], b[1] - a[1]];
                    let n = d[0].hypot(d[1]).max(1e-300);
                    let t = 2.0 * size / n;
                    let (x1, y1) = at([a[0] - t * d[0], a[1] - t * d[1]]);
                    let (x2, y2) = at([a[0] + t * d[0], a[1] + t * d[1]]);
                    segment(x1, y1, x2, y2, colour, line_width)
                        .set(
                            "stroke-dasharray",
                            format!("{} {}", 4.0 * line_width, 2.0 * line_width),
                        )
                        .add(title)
                        .into()
                })
            }
            Geometry::Circle { center, radius } | Geometry::Sphere { center, radius } => {
                center.as_ref().and_then(|c| xy(c)).zip(radius.as_ref().map(f)).map(|(c, r)| {
                    let (cx, cy) = at(c);
                    Circle::new()
                        .set("cx", cx)
                        .set("cy", cy)
                        .set("r", r.abs())
                        .set("stroke", colour)
                        .set("stroke-width", line_width)
                        .add(title)
                        .into()
                })
            }
            Geometry::Arc { center, radius, start, end } => {
                let c = center.as_ref().and_then(|c| xy(c));
                let r = radius.as_ref().map(f);
                match (c, r, anchor(system, *start), anchor(system, *end)) {
                    (Some(_), Some(r), Some(s), Some(t)) => {
                        // Counter-clockwise from start to end in the model: clockwise once y is
                        // negated (sweep flag 0), the large arc when the turn exceeds π.
                        let c = c.unwrap_or_default();
                        let angle = |p: P| (p[1] - c[1]).atan2(p[0] - c[0]);
                        let turn = (angle(t) - angle(s)).rem_euclid(std::f64::consts::TAU);
                        let large = u8::from(turn > std::f64::consts::PI);
                        let ((sx, sy), (tx, ty)) = (at(s), at(t));
                        let d = format!("M {sx} {sy} A {r} {r} 0 {large} 0 {tx} {ty}", r = r.abs());
                        Some(
                            Path::new()
                                .set("d", d)
                                .set("stroke", colour)
                                .set("stroke-width", line_width)
                                .add(title)
                                .into(),
                        )
                    }
                    _ => None,
                }
            }
            Geometry::BSpline { poles, periodic, .. } => spline_points(system, e).map(|curve| {
                let polyline = |points: &mut dyn Iterator<Item = P>| {
                    let mut d = String::new();
                    for (i, p) in points.enumerate() {
                        let (x, y) = at(p);
                        d.push_str(&format!("{} {x} {y} ", if i == 0 { "M" } else { "L" }));
                    }
                    d.trim_end().to_owned()
                };
                // The control polygon, thin and dashed, under the curve.
                let mut corners =
                    poles.iter().filter_map(|p| anchor(system, *p)).collect::<Vec<P>>();
                if *periodic && let Some(first) = corners.first().copied() {
                    corners.push(first);
                }
                Group::new()
                    .add(
                        Path::new()
                            .set("d", polyline(&mut corners.into_iter()))
                            .set("stroke", colour)
                            .set("stroke-width", 0.3 * line_width)
                            .set(
                                "stroke-dasharray",
                                format!("{} {}", 2.0 * line_width, 2.0 * line_width),
                            ),
                    )
                    .add(
                        Path::new()
                            .set("d", polyline(&mut curve.into_iter()))
                            .set("stroke", colour)
                            .set("stroke-width", line_width)
                            .set("stroke-linejoin", "round")
                            .add(title),
                    )
                    .into()
            }),
            _ => None,
        };
        if let Some(shape) = shape {
            // Construction geometry: dashed and lighter, as CAD programs draw it.
            shapes = if entity.construction {
                let dash = format!("{} {}", 3.0 * line_width, 2.0 * line_width);
                shapes
                    .add(Group::new().set("stroke-dasharray", dash).set("opacity", 0.6).add(shape))
            } else {
                shapes.add(shape)
            };
        }
    }

    // Distances between two points: thin lines in their cluster's colour.
    let mut bars = Group::new().set("stroke-linecap", "round");
    for c in system.constraint_indices() {
        let constraint = system.constraint(c);
        let points = constraint
            .args
            .iter()
            .filter(|e| matches!(system.entity(**e).geometry, Geometry::Point { .. }))
            .filter_map(|e| anchor(system, *e))
            .collect::<Vec<P>>();
        let [a, b] = points.as_slice() else { continue };
        if constraint.kind != gcs_model::ConstraintKind::Distance || constraint.args.len() != 2 {
            continue;
        }
        let colour = report
            .clusters
            .iter()
            .position(|k| k.constraints.contains(&constraint.id))
            .map_or(LOOSE, |k| PALETTE[k % PALETTE.len()]);
        // (A distance without a value, read off the drawing, says so.)
        let title = match constraint.value.as_ref().map(f) {
            Some(value) => format!("{} (Distance {value})", constraint.id),
            None => format!("{} (Distance, no value)", constraint.id),
        };
        let ((x1, y1), (x2, y2)) = (at(*a), at(*b));
        bars = bars.add(segment(x1, y1, x2, y2, colour, 0.5 * line_width).add(Title::new(title)));
    }

    // Redundant and singular constraints, over the shapes.
    let mut marks = Group::new().set("stroke-linecap", "round");
    let anchors_of = |c: gcs_model::ConstraintIdx| -> Vec<P> {
        system.constraint(c).args.iter().filter_map(|e| anchor(system, *e)).collect()
    };
    let by_id = |id: &str| system.constraint_indices().find(|c| system.constraint(*c).id == id);
    let mut marked = |id: &str, colour: &str, what: String, width: f64| {
        let Some(c) = by_id(id) else { return };
        let title = Title::new(format!("{id} ({}): {what}", system.constraint(c).kind.name()));
        let points = anchors_of(c);
        match points.as_slice() {
            [a, b, ..] => {
                let ((x1, y1), (x2, y2)) = (at(*a), at(*b));
                marks = std::mem::take(&mut marks).add(
                    segment(x1, y1, x2, y2, colour, width).set("stroke-opacity", 0.8).add(title),
                );
            }
            [a] => {
                let (cx, cy) = at(*a);
                marks = std::mem::take(&mut marks).add(
                    Circle::new()
                        .set("cx", cx)
                        .set("cy", cy)
                        .set("r", 2.5 * dot)
                        .set("fill", "none")
                        .set("stroke", colour)
                        .set("stroke-width", width)
                        .add(title),
                );
            }
            [] => {}
        }
    };
    for r in &report.redundant {
        let (colour, verdict) = match r.conflicting {
            Some(true) => (CONFLICTING, "conflicting: change one value or delete one of"),
            Some(false) => (REDUNDANT, "redundant (consistent): remove it or one of"),
            None => (REDUNDANT, "redundant: remove it or one of"),
        };
        marked(
            &r.constraint,
            colour,
            format!("{verdict} {}", r.spanning_group.join(", ")),
            3.0 * line_width,
        );
    }
    if let Some(sketch) = report.sketch.as_ref().filter(|s| s.singular) {
        for d in &sketch.dependent {
            let what = format!(
                "dependent at this drawing (singular) with {}",
                d.spanning_group.join(", ")
            );
            marked(&d.constraint, SINGULAR, what, 2.0 * line_width);
        }
    }

    // The free motions: arrows at the points, in the direction each motion moves them.
    let mut arrows = Group::new().set("stroke-linecap", "round").set("stroke", MOTION);
    let layout = gcs_jacobian::Layout::new(system);
    for (k, m) in motions.iter().enumerate() {
        if m.len() != layout.ncols() {
            continue;
        }
        let velocities: Vec<(P, P)> = system
            .entity_indices()
            .filter(|e| matches!(system.entity(*e).geometry, Geometry::Point { .. }))
            .filter_map(|e| {
                let c = layout.columns(e).start;
                Some((anchor(system, e)?, [m[c], m[c + 1]]))
            })
            .collect();
        let longest = velocities.iter().map(|(_, v)| v[0].hypot(v[1])).fold(0.0, f64::max);
        if longest.is_nan() || longest <= 0.0 {
            continue;
        }
        let scale = 0.07 * size / longest;
        let title = format!(
            "free motion {} of {}: the drawing can move this way without breaking a constraint",
            k + 1,
            motions.len()
        );
        for (p, v) in velocities {
            if v[0].hypot(v[1]) <= 1e-6 * longest {
                continue;
            }
            let q = [p[0] + scale * v[0], p[1] + scale * v[1]];
            let ((x1, y1), (x2, y2)) = (at(p), at(q));
            // The head: two short strokes back from the tip.
            let (dx, dy) = (x2 - x1, y2 - y1);
            let len = dx.hypot(dy).max(1e-300);
            let (ux, uy) = (dx / len, dy / len);
            let h = (0.3 * len).min(0.02 * size);
            let d = format!(
                "M {x1} {y1} L {x2} {y2} M {} {} L {x2} {y2} L {} {}",
                x2 - h * (ux - 0.5 * uy),
                y2 - h * (uy + 0.5 * ux),
                x2 - h * (ux + 0.5 * uy),
                y2 - h * (uy - 0.5 * ux),
            );
            arrows = arrows.add(
                Path::new()
                    .set("d", d)
                    .set("fill", "none")
                    .set("stroke-width", 1.5 * line_width)
                    .add(Title::new(title.as_str())),
            );
        }
    }

    // The verdict, above the drawing.
    let verdict = if report.rigid {
        if report.redundant.is_empty() {
            "well-constrained"
        } else {
            "over-constrained (rigid, redundant constraints)"
        }
    } else if report.redundant.is_empty() {
        "under-constrained"
    } else {
        "under-constrained, with redundant constraints"
    };
    let mut lines = vec![
        format!("{}: {verdict}", report.model),
        format!(
            "DOF {} · {} rigid cluster{} (a colour each) · {} redundant (orange; red: conflicting)",
            report.dof,
            report.clusters.len(),
            if report.clusters.len() == 1 { "" } else { "s" },
            report.redundant.len()
        ),
    ];
    if let Some(sketch) = report.sketch.as_ref().filter(|s| s.singular) {
        let kinds: Vec<String> = sketch
            .configurations
            .iter()
            .map(|c| format!("{} {}", c.kind, c.entities.join(", ")))
            .collect();
        lines.push(format!(
            "singular at this drawing (magenta): {} extra motion{}{}",
            sketch.extra_motions,
            if sketch.extra_motions == 1 { "" } else { "s" },
            if kinds.is_empty() { String::new() } else { format!(" — {}", kinds.join("; ")) }
        ));
    }
    if !motions.is_empty() {
        lines.push(format!(
            "{} free motion{} at this drawing (grey arrows, one set each)",
            motions.len(),
            if motions.len() == 1 { "" } else { "s" }
        ));
    }
    if report.dim == 3 {
        lines.push("3D model: projected onto the xy plane".to_owned());
    }
    let mut text =
        Group::new().set("font-family", "sans-serif").set("font-size", font).set("fill", "#222");
    for (k, l) in lines.iter().enumerate() {
        text = text.add(
            Text::new(l.as_str())
                .set("x", x0 + 0.5 * font)
                .set("y", y0 - head + (k as f64 + 1.3) * 1.3 * font),
        );
    }

    Document::new()
        .set("viewBox", (x0, y0 - head, w, h + head))
        .set("width", 800)
        .set("height", (800.0 * (h + head) / w).round())
        .add(Title::new(format!("{} — {}", report.file, report.model)))
        .add(text)
        .add(bars)
        .add(shapes)
        .add(marks)
        .add(arrows)
        .to_string()
}

fn segment(x1: f64, y1: f64, x2: f64, y2: f64, colour: &str, width: f64) -> Line {
    Line::new()
        .set("x1", x1)
        .set("y1", y1)
        .set("x2", x2)
        .set("y2", y2)
        .set("stroke", colour)
        .set("stroke-width", width)
}

/// The W-decomposition (`--decompose`) drawn as a tree, the SVG beside `--dot`'s Graphviz: a
/// box per rigid subsystem — its entities (points and curves; segments by their points), how
/// many constraints, the whole list as a tooltip —, leaves in light blue, each subsystem over
/// the subsystems it decomposes into; several trees (one per component) side by side.
pub fn plan_svg(system: &System, trees: &[gcs_analysis::DecompositionNode]) -> String {
    const W: f64 = 190.0;
    const H: f64 = 64.0;
    const GAP_X: f64 = 20.0;
    const GAP_Y: f64 = 46.0;
    const FONT: f64 = 11.0;
    /// Lays `node` out: its leaves get the next slots; returns its centre's slot.
    fn place(
        node: &gcs_analysis::DecompositionNode,
        depth: usize,
        next: &mut f64,
        out: &mut Vec<(f64, usize, Option<usize>, usize)>,
        parent: Option<usize>,
    ) -> f64 {
        let me = out.len();
        out.push((0.0, depth, parent, me));
        let x = if node.children.is_empty() {
            *next += 1.0;
            *next - 1.0
        } else {
            let xs: Vec<f64> =
                node.children.iter().map(|c| place(c, depth + 1, next, out, Some(me))).collect();
            xs.iter().sum::<f64>() / xs.len() as f64
        };
        out[me].0 = x;
        x
    }
    // Breadth of the layout: (slot, depth, parent, index) per node, in preorder.
    let mut laid = Vec::new();
    let mut next = 0.0;
    for t in trees {
        place(t, 0, &mut next, &mut laid, None);
    }
    let all: Vec<&gcs_analysis::DecompositionNode> = {
        // (The preorder walk again, by reference: the same order as `laid`.)
        fn walk<'a>(
            n: &'a gcs_analysis::DecompositionNode,
            out: &mut Vec<&'a gcs_analysis::DecompositionNode>,
        ) {
            out.push(n);
            for c in &n.children {
                walk(c, out);
            }
        }
        let mut v = Vec::new();
        for t in trees {
            walk(t, &mut v);
        }
        v
    };
    let depth = laid.iter().map(|l| l.1).max().unwrap_or(0);
    let width = (next.max(1.0)) * (W + GAP_X) + GAP_X;
    let height = (depth + 1) as f64 * (H + GAP_Y) + GAP_Y;
    let corner = |slot: f64, d: usize| (GAP_X + slot * (W + GAP_X), GAP_Y + d as f64 * (H + GAP_Y));
    let mut edges = Group::new().set("stroke", "#888").set("stroke-width", 1.2);
    let mut boxes = Group::new().set("font-family", "sans-serif").set("font-size", FONT);
    for (k, (slot, d, parent, _)) in laid.iter().enumerate() {
        let (x, y) = corner(*slot, *d);
        if let Some(p) = parent {
            let (px, py) = corner(laid[*p].0, laid[*p].1);
            edges = edges.add(segment(px + W / 2.0, py + H, x + W / 2.0, y, "#888", 1.2));
        }
        let node = all[k];
        let ids: Vec<&str> = (node.entities.iter())
            .filter(|e| !system.entity(**e).kind().is_composite())
            .map(|e| system.entity(*e).id.as_str())
            .collect();
        let mut lines: Vec<String> = ids.chunks(6).map(|c| c.join(" ")).collect();
        if lines.len() > 3 {
            lines.truncate(3);
            lines[2].push_str(" …");
        }
        lines.push(format!(
            "{} constraint{}{}",
            node.constraints.len(),
            if node.constraints.len() == 1 { "" } else { "s" },
            if node.children.is_empty() { " (leaf)" } else { "" }
        ));
        let leaf = node.children.is_empty();
        let mut g =
            Group::new().add(Title::new(format!("{} entities: {}", ids.len(), ids.join(", "))));
        g = g.add(
            svg::node::element::Rectangle::new()
                .set("x", x)
                .set("y", y)
                .set("width", W)
                .set("height", H)
                .set("rx", 6)
                .set("fill", if leaf { "#e8f1fa" } else { "#ffffff" })
                .set("stroke", PALETTE[0])
                .set("stroke-width", if leaf { 1.0 } else { 2.2 }),
        );
        for (i, l) in lines.iter().enumerate() {
            g = g.add(
                Text::new(l.as_str())
                    .set("x", x + 6.0)
                    .set("y", y + 4.0 + (i as f64 + 1.0) * 1.25 * FONT)
                    .set("fill", "#222"),
            );
        }
        boxes = boxes.add(g);
    }
    Document::new()
        .set("viewBox", (0.0, 0.0, width, height))
        .set("width", width.round())
        .set("height", height.round())
        .add(Title::new(format!("W-decomposition of {}", system.name())))
        .add(edges)
        .add(boxes)
        .to_string()
}
