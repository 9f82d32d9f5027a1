//! The semantic layer: records into sketches (see the module documentation of [`super`] for
//! the rules).

use std::collections::{HashMap, HashSet};

use num_rational::BigRational;
use num_traits::{Signed, Zero};

use super::codes::{constraint as ct, entity as et, group as gt, request as rt};
use super::geom::{self, Frame, Quat, V3};
use super::parse::{Constraint, Entity, File, Group, Num, Request};
use crate::ImportError;
use crate::ir::{self, Geometry, Kind, Number, Part, Ref, Skipped};

/// Why an item cannot be read: skipped (with the reason), or the file is inconsistent (an
/// error at the item's line).
enum Fail {
    Skip(String),
    Bad(String),
}

type R<T> = Result<T, Fail>;

fn skip<T>(msg: impl Into<String>) -> R<T> {
    Err(Fail::Skip(msg.into()))
}

fn eid(h: u32) -> String {
    format!("e.{h:08x}")
}

fn cid(h: u32) -> String {
    format!("c.{h:08x}")
}

/// The IR gaps, worded once.
const GAP_CIRCLE_3D: &str = "a circle or arc in a 3D sketch needs its normal (its plane), which \
                             the IR's Circle and Arc do not have";
const GAP_PLANE_3D: &str = "a plane reference in a 3D sketch: the IR's PointOnObject, Distance \
                            and Symmetric take no plane";

/// Where an entity comes from, seen from the group being read.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum Origin {
    /// Made by one of this group's requests: free geometry of the sketch.
    Own,
    /// From an earlier group, or a fixed copy made by this drawing group (its workplane and
    /// origin): fixed where it is drawn.
    External,
    /// Made by this (extrude, lathe, translate, link…) group's operation from its own
    /// parameters.
    Generated,
}

/// The group of an entity: its request's, or the group that generated it.
fn entity_group(f: &File, h: u32) -> Option<u32> {
    if h & 0x8000_0000 != 0 {
        Some((h >> 16) & 0x3fff)
    } else {
        f.request_index.get(&(h >> 16)).map(|&i| f.requests[i].group)
    }
}

/// What a non-drawing group's operation is parametrised by.
fn operation(ty: i64) -> &'static str {
    match ty {
        5100 => "extrusion vector",
        5101..=5103 => "axis and angle of revolution",
        5200 => "rotation",
        5201 => "translation",
        5300 => "placement of the linked part",
        _ => "operation",
    }
}

/// The named point of curve `e` that its `point[i]` is.
fn part_of(e: &Entity, i: usize, swapped: bool) -> Option<Part> {
    match (e.ty, i) {
        (et::LINE_SEGMENT, 0) => Some(Part::Start),
        (et::LINE_SEGMENT, 1) => Some(Part::End),
        (et::CIRCLE | et::ARC_OF_CIRCLE, 0) => Some(Part::Center),
        (et::ARC_OF_CIRCLE, 1) => Some(if swapped { Part::End } else { Part::Start }),
        (et::ARC_OF_CIRCLE, 2) => Some(if swapped { Part::Start } else { Part::End }),
        (et::CUBIC, 0) => Some(Part::Start),
        (et::CUBIC, 1) => Some(Part::Pole(1)),
        (et::CUBIC, 2) => Some(Part::Pole(2)),
        (et::CUBIC, 3) => Some(Part::End),
        (et::WORKPLANE, 0) => Some(Part::Origin),
        _ => None,
    }
}

fn rat(n: &Number) -> BigRational {
    n.0.clone()
}

/// Every sketch of a parsed file.
pub(super) fn sketches(file: &str, stem: &str, f: &File) -> Result<Vec<ir::Sketch>, ImportError> {
    let mut out = Vec::new();
    for g in &f.groups {
        if g.h == 1 {
            // The references (the three base workplanes): never a sketch of its own.
            continue;
        }
        let requests: Vec<&Request> = f.requests.iter().filter(|r| r.group == g.h).collect();
        let constraints: Vec<&Constraint> =
            f.constraints.iter().filter(|c| c.group == g.h).collect();
        if requests.is_empty() && constraints.is_empty() {
            continue;
        }
        let frame = frame_of(file, f, g, &requests, &constraints)?;
        let mut b = Builder {
            f,
            g,
            drawing: matches!(g.ty, gt::DRAWING_3D | gt::DRAWING_WORKPLANE),
            frame,
            entities: Vec::new(),
            ids: HashSet::new(),
            own_skipped: HashMap::new(),
            staging: Vec::new(),
            skipped: Vec::new(),
            notes: Vec::new(),
        };
        if !b.drawing {
            b.skipped.push(Skipped {
                item: format!("g{}", g.h),
                reason: format!(
                    "{} group ({}): the parameters of its operation (the {}) are unknowns of \
                     this group that the IR cannot hold; the entities it generates are not \
                     included",
                    gt::name(g.ty),
                    g.ty,
                    operation(g.ty)
                ),
            });
        }
        for r in &requests {
            b.own_request(r).map_err(|m| {
                ImportError::new(file, m)
                    .at_line(r.line)
                    .in_element(format!("Request r.{:08x}", r.h))
            })?;
        }
        let constraints = b.constraints(&constraints).map_err(|(c, m)| {
            ImportError::new(file, m).at_line(c.line).in_element(format!("Constraint {}", cid(c.h)))
        })?;
        let mut entities = b.entities;
        entities.sort_by(|a, b| a.0.cmp(&b.0).then_with(|| a.1.id.cmp(&b.1.id)));
        out.push(ir::Sketch {
            name: format!("{stem}/g{}", g.h),
            label: (!g.name.is_empty()).then(|| g.name.clone()),
            dim: if b.frame.is_some() { 2 } else { 3 },
            entities: entities.into_iter().map(|(_, e)| e).collect(),
            constraints,
            skipped: b.skipped,
            notes: b.notes,
            source_verdict: Vec::new(),
        });
    }
    Ok(out)
}

/// The workplane a group is drawn in: the one workplane of all its requests (of all its
/// constraints when it has no requests); `None` (a 3D sketch) when they are free in 3D or in
/// several workplanes.
fn frame_of(
    file: &str,
    f: &File,
    g: &Group,
    requests: &[&Request],
    constraints: &[&Constraint],
) -> Result<Option<Frame>, ImportError> {
    let planes: Vec<u32> = if requests.is_empty() {
        constraints.iter().map(|c| c.workplane).collect()
    } else {
        requests.iter().map(|r| r.workplane).collect()
    };
    let w = planes[0];
    if w == 0 || planes.iter().any(|p| *p != w) {
        return Ok(None);
    }
    let err =
        |m: String| ImportError::new(file, m).at_line(g.line).in_element(format!("Group g{}", g.h));
    let entity = |h: u32, what: &str| -> Result<&Entity, ImportError> {
        f.entity_index
            .get(&h)
            .map(|&i| &f.entities[i])
            .ok_or_else(|| err(format!("its workplane's {what} {} is not in the file", eid(h))))
    };
    let wp = entity(w, "entity")?;
    if wp.ty != et::WORKPLANE {
        return Err(err(format!(
            "it is drawn in {}, a {} rather than a workplane",
            eid(w),
            et::name(wp.ty)
        )));
    }
    let origin = entity(wp.points[0], "origin")?;
    let normal = entity(wp.normal, "normal")?;
    let (Some(o), Some(q)) = (finite3(&origin.act_point), finite4(&normal.act_normal)) else {
        return Err(err(format!("its workplane {} has no finite position", eid(w))));
    };
    let q = Quat([rat(q[0]), rat(q[1]), rat(q[2]), rat(q[3])]);
    let frame = Frame { h: w, origin: V3::from_numbers(o), u: q.u(), v: q.v(), n: q.n() };
    if geom::norm(frame.n.f64()) < 1e-6 {
        return Err(err(format!("its workplane {} has a zero normal", eid(w))));
    }
    Ok(Some(frame))
}

fn finite3(p: &[Num; 3]) -> Option<[&Number; 3]> {
    match p {
        [Some(x), Some(y), Some(z)] => Some([x, y, z]),
        _ => None,
    }
}

fn finite4(p: &[Num; 4]) -> Option<[&Number; 4]> {
    match p {
        [Some(w), Some(x), Some(y), Some(z)] => Some([w, x, y, z]),
        _ => None,
    }
}

/// The outcome of one constraint.
enum Outcome {
    Emit(ir::Constraint),
    Skip(String),
    /// Not imported, and nothing lost: said by another constraint, or not geometry.
    Note(String),
}

/// The references of a constraint being built, and the first one off the workplane.
#[derive(Default)]
struct Refs {
    refs: Vec<Ref>,
    off: Option<String>,
}

impl Refs {
    fn add(&mut self, (r, off): (Ref, bool)) {
        if off && self.off.is_none() {
            self.off = Some(r.entity.clone());
        }
        self.refs.push(r);
    }
}

struct Builder<'a> {
    f: &'a File,
    g: &'a Group,
    /// A DRAWING_3D or DRAWING_WORKPLANE group.
    drawing: bool,
    /// The workplane of a 2D sketch.
    frame: Option<Frame>,
    /// The entities so far, with their source order.
    entities: Vec<(usize, ir::Entity)>,
    ids: HashSet<String>,
    /// Own entities that could not be expressed, with the reason.
    own_skipped: HashMap<u32, String>,
    /// External entities needed by the constraint being read, added when it is emitted.
    staging: Vec<(usize, ir::Entity)>,
    skipped: Vec<Skipped>,
    notes: Vec<Skipped>,
}

impl<'a> Builder<'a> {
    fn ent(&self, h: u32, role: &str) -> R<&'a Entity> {
        if h == 0 {
            return Err(Fail::Bad(format!("no {role}")));
        }
        let f: &'a File = self.f;
        match f.entity_index.get(&h) {
            Some(&i) => Ok(&f.entities[i]),
            None => Err(Fail::Bad(format!("{role} {} is not in the file", eid(h)))),
        }
    }

    fn origin(&self, h: u32) -> R<Origin> {
        match entity_group(self.f, h) {
            None => Err(Fail::Bad(format!(
                "{} belongs to request r.{:08x}, which is not in the file",
                eid(h),
                h >> 16
            ))),
            Some(g) if g == self.g.h => {
                if h & 0x8000_0000 == 0 {
                    Ok(Origin::Own)
                } else if self.drawing {
                    Ok(Origin::External)
                } else {
                    Ok(Origin::Generated)
                }
            }
            Some(_) => Ok(Origin::External),
        }
    }

    fn generated(&self, h: u32) -> String {
        format!(
            "{} is generated by this {} group from the parameters of its operation (the {}), \
             which the IR cannot hold",
            eid(h),
            gt::name(self.g.ty),
            operation(self.g.ty)
        )
    }

    fn own_skipped_reason(&self, h: u32) -> Option<String> {
        self.own_skipped.get(&h).map(|r| format!("{} is skipped ({r})", eid(h)))
    }

    fn pos3(&self, e: &Entity) -> R<V3> {
        match finite3(&e.act_point) {
            Some(p) => Ok(V3::from_numbers(p)),
            None => skip(format!("{} has a non-finite position", eid(e.h))),
        }
    }

    fn param(&self, h: u32) -> Option<&'a Number> {
        let f: &'a File = self.f;
        f.params.get(&h).and_then(Option::as_ref)
    }

    /// The `n` parameters of a request's point (`u, v` or `x, y, z`), when the file has them.
    fn point_params(&self, e: &Entity, n: usize) -> Option<Vec<Number>> {
        if e.h & 0x8000_0000 != 0 {
            return None;
        }
        let k = e.h & 0xffff;
        let i = if k == 0 { 0 } else { k - 1 };
        if i >= 12 {
            return None;
        }
        let base = (e.h & 0xffff_0000) | (16 + 3 * i);
        (0..n as u32).map(|j| self.param(base + j).cloned()).collect()
    }

    /// A point's coordinates in the sketch, and whether it lies off the workplane.
    fn point_coords(&self, e: &Entity) -> R<(Vec<Number>, bool)> {
        match &self.frame {
            Some(fr) => {
                if e.ty == et::POINT_IN_2D
                    && e.workplane == fr.h
                    && let Some(uv) = self.point_params(e, 2)
                {
                    return Ok((uv, false));
                }
                let p = self.pos3(e)?;
                let [u, v] = fr.project(&p);
                Ok((vec![Number(u), Number(v)], !fr.contains(&p)))
            }
            None => {
                if e.ty == et::POINT_IN_3D
                    && let Some(xyz) = self.point_params(e, 3)
                {
                    return Ok((xyz, false));
                }
                Ok((self.pos3(e)?.coords(), false))
            }
        }
    }

    fn point_of(&self, e: &Entity, i: usize) -> R<(Vec<Number>, bool)> {
        let p = self.ent(e.points[i], &format!("point[{i}] of {}", eid(e.h)))?;
        if !et::is_point(p.ty) {
            return Err(Fail::Bad(format!(
                "point[{i}] of {} is a {}, not a point",
                eid(e.h),
                et::name(p.ty)
            )));
        }
        self.point_coords(p)
    }

    /// A normal entity's orientation (its parameters for a free normal of a request).
    fn quat(&self, e: &Entity) -> R<Quat> {
        if e.ty == 3000 && e.h & 0x8000_0000 == 0 {
            let base = (e.h & 0xffff_0000) | 32;
            let q: Option<Vec<&Number>> = (0..4).map(|j| self.param(base + j)).collect();
            if let Some(q) = q {
                return Ok(Quat([rat(q[0]), rat(q[1]), rat(q[2]), rat(q[3])]));
            }
        }
        match finite4(&e.act_normal) {
            Some(q) => Ok(Quat([rat(q[0]), rat(q[1]), rat(q[2]), rat(q[3])])),
            None => skip(format!("{} has a non-finite orientation", eid(e.h))),
        }
    }

    fn radius(&self, e: &Entity) -> R<BigRational> {
        let d = self.ent(e.distance, &format!("distance of {}", eid(e.h)))?;
        let r = match (d.ty == et::DISTANCE).then(|| self.param(d.h)).flatten() {
            Some(r) => Some(r),
            None => d.act_distance.as_ref(),
        };
        match r {
            Some(r) if r.0.is_positive() => Ok(rat(r)),
            Some(_) => skip(format!("{} has a zero or negative radius", eid(e.h))),
            None => skip(format!("{} has a non-finite radius", eid(e.h))),
        }
    }

    /// The geometry of a curve (or workplane), whether it lies off the workplane, and whether
    /// an arc was reversed (its normal against the workplane's).
    fn curve_geometry(&self, e: &Entity) -> R<(Geometry, bool, bool)> {
        let h = eid(e.h);
        match e.ty {
            et::LINE_SEGMENT => {
                let (start, o1) = self.point_of(e, 0)?;
                let (end, o2) = self.point_of(e, 1)?;
                if self.frame.is_some() && start == end && e.h & 0x8000_0000 != 0 {
                    return skip(format!("{h} is seen end-on from the workplane"));
                }
                Ok((Geometry::Segment { start, end }, o1 || o2, false))
            }
            et::CIRCLE | et::ARC_OF_CIRCLE => {
                let Some(fr) = &self.frame else { return skip(GAP_CIRCLE_3D) };
                let n = self.quat(self.ent(e.normal, &format!("normal of {h}"))?)?.n();
                if !fr.normal_parallel(&n) {
                    return skip(format!(
                        "{h} is not parallel to the workplane: seen from it, it is an ellipse"
                    ));
                }
                let swapped = n.dot(&fr.n).is_negative();
                let (center, off) = self.point_of(e, 0)?;
                if e.ty == et::CIRCLE {
                    let radius = Number(self.radius(e)?);
                    return Ok((Geometry::Circle { center, radius }, off, false));
                }
                let (mut start, _) = self.point_of(e, 1)?;
                let (mut end, _) = self.point_of(e, 2)?;
                if start == center {
                    return skip(format!("{h} has a zero radius"));
                }
                if swapped {
                    std::mem::swap(&mut start, &mut end);
                }
                Ok((Geometry::Arc { center, start, end }, off, swapped))
            }
            et::CUBIC if e.extra_points == 0 => {
                let mut poles = Vec::with_capacity(4);
                let mut off = false;
                for i in 0..4 {
                    let (p, o) = self.point_of(e, i)?;
                    off |= o;
                    poles.push(p);
                }
                let knots = vec![(Number::from_i64(0), 4), (Number::from_i64(1), 4)];
                let geometry =
                    Geometry::BSpline { degree: 3, poles, weights: None, knots, periodic: false };
                Ok((geometry, off, false))
            }
            et::CUBIC => skip(format!(
                "cubic spline through {} points (extraPoints={}): SolveSpace interpolates them \
                 with a C2 spline whose on-curve points are not B-spline poles",
                e.extra_points.saturating_add(2),
                e.extra_points
            )),
            et::CUBIC_PERIODIC => skip(
                "periodic cubic spline (CUBIC_PERIODIC): SolveSpace interpolates its points with \
                 a closed C2 spline whose on-curve points are not B-spline poles",
            ),
            et::WORKPLANE if self.frame.is_none() => {
                let (origin, _) = self.point_of(e, 0)?;
                let n = self.quat(self.ent(e.normal, &format!("normal of {h}"))?)?.n();
                Ok((Geometry::Plane { origin, normal: n.coords() }, false, false))
            }
            et::WORKPLANE => skip("a workplane drawn in a 2D sketch"),
            15000 => skip("text (TTF_TEXT): not geometry the IR knows"),
            16000 => skip("image (IMAGE): not geometry the IR knows"),
            ty => skip(format!("entity type {ty} ({}) is not supported", et::name(ty))),
        }
    }

    fn push_entity(&mut self, order: usize, entity: ir::Entity) {
        if self.ids.insert(entity.id.clone()) {
            self.entities.push((order, entity));
        }
    }

    fn stage(&mut self, order: usize, id: String, geometry: Geometry, construction: bool) {
        if self.ids.contains(&id) || self.staging.iter().any(|(_, e)| e.id == id) {
            return;
        }
        self.staging.push((order, ir::Entity { id, geometry, construction, external: true }));
    }

    fn geometry_by_id(&self, id: &str) -> Option<&Geometry> {
        self.entities
            .iter()
            .chain(self.staging.iter())
            .find(|(_, e)| e.id == id)
            .map(|(_, e)| &e.geometry)
    }

    /// One of this group's requests: its entity, or a skipped item.
    fn own_request(&mut self, r: &Request) -> Result<(), String> {
        let h = r.h << 16;
        let e = match self.f.entity_index.get(&h) {
            Some(&i) => &self.f.entities[i],
            None => return Err(format!("its entity {} is not in the file", eid(h))),
        };
        let geometry = if self.frame.is_none() && r.workplane != 0 {
            skip(format!(
                "drawn in workplane {} inside a 3D group: its points are confined to that \
                 plane, which the IR cannot state (no point-on-plane constraint)",
                eid(r.workplane)
            ))
        } else if r.ty == rt::DATUM_POINT {
            if et::is_point(e.ty) {
                self.point_coords(e).map(|(at, _)| Geometry::Point { at })
            } else {
                Err(Fail::Bad(format!("datum point {} is a {}", eid(h), et::name(e.ty))))
            }
        } else if r.ty == rt::WORKPLANE && e.ty != et::WORKPLANE {
            Err(Fail::Bad(format!("workplane {} is a {}", eid(h), et::name(e.ty))))
        } else {
            self.curve_geometry(e).map(|(g, _, _)| g)
        };
        match geometry {
            Ok(geometry) => {
                let entity = ir::Entity {
                    id: eid(h),
                    geometry,
                    construction: e.construction,
                    external: false,
                };
                self.push_entity(e.index, entity);
                Ok(())
            }
            Err(Fail::Skip(reason)) => {
                self.skipped.push(Skipped { item: eid(h), reason: reason.clone() });
                self.own_skipped.insert(h, reason);
                Ok(())
            }
            Err(Fail::Bad(m)) => Err(m),
        }
    }

    /// Makes sure a curve is in the sketch (own, or staged as external): its id and whether
    /// it was reversed; `None` for an external curve the sketch cannot show (its points are
    /// then taken on their own).
    fn ensure_curve(&mut self, e: &Entity) -> R<Option<(String, bool)>> {
        match self.origin(e.h)? {
            Origin::Own => match self.own_skipped_reason(e.h) {
                Some(r) => skip(r),
                None => Ok(Some((eid(e.h), false))),
            },
            Origin::Generated => skip(self.generated(e.h)),
            Origin::External => match self.curve_geometry(e) {
                Ok((geometry, _, swapped)) => {
                    self.stage(e.index, eid(e.h), geometry, e.construction);
                    Ok(Some((eid(e.h), swapped)))
                }
                Err(Fail::Skip(_)) => Ok(None),
                Err(bad) => Err(bad),
            },
        }
    }

    /// A whole curve referenced by a constraint, and whether it lies off the workplane.
    fn whole_curve(&mut self, e: &Entity) -> R<(Ref, bool)> {
        match self.origin(e.h)? {
            Origin::Own => match self.own_skipped_reason(e.h) {
                Some(r) => skip(r),
                None => Ok((Ref::whole(eid(e.h)), false)),
            },
            Origin::Generated => skip(self.generated(e.h)),
            Origin::External => {
                let (geometry, off, _) = self.curve_geometry(e)?;
                self.stage(e.index, eid(e.h), geometry, e.construction);
                Ok((Ref::whole(eid(e.h)), off))
            }
        }
    }

    /// A point referenced by a constraint: a curve's named point when it is one, else a point
    /// entity of its own.
    fn point(&mut self, h: u32, role: &str) -> R<(Ref, bool)> {
        let e = self.ent(h, role)?;
        if !et::is_point(e.ty) {
            return skip(format!("{role} {} is a {}, not a point", eid(h), et::name(e.ty)));
        }
        let origin = self.origin(h)?;
        if origin == Origin::Generated {
            return skip(self.generated(h));
        }
        if h & 0x8000_0000 == 0 && h & 0xffff != 0 {
            let primary = h & 0xffff_0000;
            if let Some(&pi) = self.f.entity_index.get(&primary) {
                let pe = &self.f.entities[pi];
                let as_part = match pe.ty {
                    et::LINE_SEGMENT | et::CIRCLE | et::ARC_OF_CIRCLE | et::CUBIC => true,
                    et::WORKPLANE => self.frame.is_none() && origin == Origin::Own,
                    _ => false,
                };
                if let (true, Some(i)) = (as_part, pe.points.iter().position(|&p| p == h)) {
                    if let Some((id, swapped)) = self.ensure_curve(pe)?
                        && let Some(part) = part_of(pe, i, swapped)
                    {
                        let off =
                            if origin == Origin::Own { false } else { self.point_coords(e)?.1 };
                        return Ok((Ref::part(id, part), off));
                    }
                } else if origin == Origin::Own
                    && let Some(r) = self.own_skipped_reason(primary)
                {
                    return skip(r);
                }
            }
        }
        let id = eid(h);
        if origin == Origin::Own && self.ids.contains(&id) {
            return Ok((Ref::whole(id), false));
        }
        if let Some(r) = self.own_skipped_reason(h) {
            return skip(r);
        }
        let (at, off) = self.point_coords(e)?;
        if origin == Origin::Own {
            let entity = ir::Entity {
                id: id.clone(),
                geometry: Geometry::Point { at },
                construction: e.construction,
                external: false,
            };
            self.push_entity(e.index, entity);
            return Ok((Ref::whole(id), false));
        }
        self.stage(e.index, id.clone(), Geometry::Point { at }, e.construction);
        Ok((Ref::whole(id), off))
    }

    fn segment(&mut self, h: u32, role: &str) -> R<(Ref, bool)> {
        let e = self.ent(h, role)?;
        if e.ty != et::LINE_SEGMENT {
            return skip(format!("{role} {} is a {}, not a line segment", eid(h), et::name(e.ty)));
        }
        self.whole_curve(e)
    }

    fn circle(&mut self, h: u32, role: &str, arc_only: bool) -> R<(Ref, bool)> {
        let e = self.ent(h, role)?;
        let ok = e.ty == et::ARC_OF_CIRCLE || (!arc_only && e.ty == et::CIRCLE);
        if !ok {
            let what = if arc_only { "an arc" } else { "a circle or arc" };
            return skip(format!("{role} {} is a {}, not {what}", eid(h), et::name(e.ty)));
        }
        self.whole_curve(e)
    }

    /// An entity used for its direction (SolveSpace's `VectorGetExprs`): a segment, or a normal
    /// or face as a fixed infinite line. Lines made here run along minus the SolveSpace vector,
    /// as segments do (SolveSpace's vector of a segment is start − end).
    fn vector(&mut self, h: u32, role: &str) -> R<(Ref, bool)> {
        let e = self.ent(h, role)?;
        if e.ty == et::LINE_SEGMENT {
            return self.whole_curve(e);
        }
        let origin = self.origin(h)?;
        if origin == Origin::Generated {
            return skip(self.generated(h));
        }
        if et::is_normal(e.ty) {
            if e.ty == 3000 && origin == Origin::Own {
                return skip(format!(
                    "{role} {} is a free normal of this group (an orientation unknown): the IR \
                     has no direction entity",
                    eid(h)
                ));
            }
            let n = self.quat(e)?.n();
            let anchor = match e.points[0] {
                0 => V3::zero(),
                p => self.pos3(self.ent(p, "point of a normal")?)?,
            };
            return self.direction_line(e, eid(h), anchor, n);
        }
        if et::is_face(e.ty) {
            let n = match &e.act_normal {
                [_, Some(x), Some(y), Some(z)] => V3::from_numbers([x, y, z]),
                _ => return skip(format!("{} has a non-finite normal", eid(h))),
            };
            let anchor = self.pos3(e)?;
            return self.direction_line(e, format!("{}.normal", eid(h)), anchor, n);
        }
        skip(format!("{role} {} is a {}, which has no direction", eid(h), et::name(e.ty)))
    }

    fn direction_line(&mut self, e: &Entity, id: String, anchor: V3, n: V3) -> R<(Ref, bool)> {
        let b = anchor.sub(&n);
        let (a, b, off) = match &self.frame {
            Some(fr) => {
                let (pa, pb) = (fr.project(&anchor), fr.project(&b));
                if pa == pb {
                    return skip(format!("{id} is perpendicular to the workplane"));
                }
                let [au, av] = pa;
                let [bu, bv] = pb;
                (
                    vec![Number(au), Number(av)],
                    vec![Number(bu), Number(bv)],
                    !fr.in_plane_direction(&n),
                )
            }
            None => {
                if n.0.iter().all(Zero::is_zero) {
                    return skip(format!("{id} has a zero direction"));
                }
                (anchor.coords(), b.coords(), false)
            }
        };
        self.stage(e.index, id.clone(), Geometry::Line { a, b }, e.construction);
        Ok((Ref::whole(id), off))
    }

    /// A workplane or face referenced as a plane: in a 2D sketch, its trace on the workplane
    /// (an infinite line), when it crosses it (at right angles when `perpendicular`).
    fn plane(&mut self, h: u32, role: &str, perpendicular: bool) -> R<(Ref, bool)> {
        let e = self.ent(h, role)?;
        let Some(fr) = self.frame.clone() else { return skip(GAP_PLANE_3D) };
        let (p0, n) = if e.ty == et::WORKPLANE {
            let o = self.pos3(self.ent(e.points[0], &format!("origin of {}", eid(h)))?)?;
            (o, self.quat(self.ent(e.normal, &format!("normal of {}", eid(h)))?)?.n())
        } else if et::is_face(e.ty) {
            let n = match &e.act_normal {
                [_, Some(x), Some(y), Some(z)] => V3::from_numbers([x, y, z]),
                _ => return skip(format!("{} has a non-finite normal", eid(h))),
            };
            (self.pos3(e)?, n)
        } else {
            return skip(format!("{role} {} is a {}, not a plane", eid(h), et::name(e.ty)));
        };
        match self.origin(h)? {
            Origin::Generated => return skip(self.generated(h)),
            Origin::Own => return skip(format!("{} is a free workplane of this group", eid(h))),
            Origin::External => {}
        }
        if fr.normal_parallel(&n) {
            return skip(format!(
                "the plane {} is parallel to the workplane: on the sketch the constraint is \
                 constant (the IR has no point-on-plane kind)",
                eid(h)
            ));
        }
        if perpendicular && !fr.in_plane_direction(&n) {
            return skip(format!(
                "the plane {} is oblique to the workplane: a distance to it is not a distance \
                 in the sketch",
                eid(h)
            ));
        }
        let a = fr.u.dot(&n);
        let b = fr.v.dot(&n);
        let c = p0.sub(&fr.origin).dot(&n);
        let s = &a * &a + &b * &b;
        if s.is_zero() {
            return skip(format!("the plane {} does not cross the workplane", eid(h)));
        }
        let fu = &a * &c / &s;
        let fv = &b * &c / &s;
        let line = Geometry::Line {
            a: vec![Number(fu.clone()), Number(fv.clone())],
            b: vec![Number(fu - &b), Number(fv + &a)],
        };
        self.stage(e.index, eid(h), line, false);
        Ok((Ref::whole(eid(h)), false))
    }

    /// An axis of the sketch's workplane (`u` or `v`), as a fixed line.
    fn axis(&mut self, which: char) -> R<(Ref, bool)> {
        let Some(fr) = &self.frame else { return skip("an axis of a workplane in a 3D sketch") };
        let id = format!("{}.{which}-axis", eid(fr.h));
        let (zero, one) = (Number::from_i64(0), Number::from_i64(1));
        let b = if which == 'u' { vec![one, zero.clone()] } else { vec![zero.clone(), one] };
        let line = Geometry::Line { a: vec![zero.clone(), zero], b };
        self.stage(usize::MAX, id.clone(), line, false);
        Ok((Ref::whole(id), false))
    }

    /// The constraints of the group, in file order, with the folded coincidences.
    fn constraints<'c>(
        &mut self,
        cs: &[&'c Constraint],
    ) -> Result<Vec<ir::Constraint>, (&'c Constraint, String)> {
        let mut outcomes: Vec<Option<Outcome>> = cs.iter().map(|_| None).collect();
        let mut folded: HashMap<usize, u32> = HashMap::new();
        let is_tangency = |c: &Constraint| {
            matches!(c.ty, ct::ARC_LINE_TANGENT | ct::CUBIC_LINE_TANGENT | ct::CURVE_CURVE_TANGENT)
        };
        // Tangencies first: each takes the coincidence that joins its curves.
        for (i, c) in cs.iter().enumerate() {
            if !is_tangency(c) {
                continue;
            }
            self.staging.clear();
            let result = self.precheck(c).and_then(|_| self.tangency(c, cs, &folded));
            outcomes[i] = Some(match result {
                Ok((constraint, k)) => {
                    folded.insert(k, c.h);
                    self.commit();
                    Outcome::Emit(constraint)
                }
                Err(Fail::Skip(reason)) => Outcome::Skip(reason),
                Err(Fail::Bad(m)) => return Err((c, m)),
            });
        }
        for (i, c) in cs.iter().enumerate() {
            if outcomes[i].is_some() {
                continue;
            }
            if let Some(t) = folded.get(&i) {
                outcomes[i] = Some(Outcome::Note(format!(
                    "POINTS_COINCIDENT (20) folded into the tangency {}: the IR's TangentAtEnds \
                     states the joint and the tangency as one constraint",
                    cid(*t)
                )));
                continue;
            }
            if c.ty == ct::COMMENT {
                outcomes[i] = Some(Outcome::Note(
                    "comment (1000): a text annotation, not a constraint".into(),
                ));
                continue;
            }
            self.staging.clear();
            let result = self.precheck(c).and_then(|in_plane| self.constraint(c, in_plane));
            outcomes[i] = Some(match result {
                Ok(constraint) => {
                    self.commit();
                    Outcome::Emit(constraint)
                }
                Err(Fail::Skip(reason)) => Outcome::Skip(reason),
                Err(Fail::Bad(m)) => return Err((c, m)),
            });
        }
        let mut out = Vec::new();
        for (c, outcome) in cs.iter().zip(outcomes) {
            match outcome {
                Some(Outcome::Emit(constraint)) => out.push(constraint),
                Some(Outcome::Skip(reason)) => {
                    self.skipped.push(Skipped { item: cid(c.h), reason });
                }
                Some(Outcome::Note(reason)) => {
                    self.notes.push(Skipped { item: cid(c.h), reason });
                }
                None => {}
            }
        }
        Ok(out)
    }

    fn commit(&mut self) {
        for (order, entity) in std::mem::take(&mut self.staging) {
            self.push_entity(order, entity);
        }
    }

    fn driving(&self, c: &Constraint) -> bool {
        !(c.reference || (self.g.all_dims_reference && ct::is_dimension(c.ty)))
    }

    /// What applies to every constraint before its type: comments, relaxed groups, the
    /// workplane it is stated in. Returns whether its references must lie in the workplane
    /// (a 2D sketch, and a constraint SolveSpace does not project into it).
    fn precheck(&self, c: &Constraint) -> R<bool> {
        let name = ct::name(c.ty);
        if c.ty == ct::COMMENT {
            return skip("comment (1000): a text annotation, not a constraint");
        }
        if self.g.relax_constraints && c.ty != ct::POINTS_COINCIDENT {
            return skip(format!(
                "{name} ({}) is not solved: the group relaxes its constraints \
                 (Group.relaxConstraints=1)",
                c.ty
            ));
        }
        let needs_workplane = matches!(
            c.ty,
            ct::HORIZONTAL
                | ct::VERTICAL
                | ct::SYMMETRIC_HORIZ
                | ct::SYMMETRIC_VERT
                | ct::SYMMETRIC_LINE
        );
        if c.workplane == 0 && needs_workplane {
            return skip(format!("{name} ({}) stated in 3D: it needs a workplane", c.ty));
        }
        match &self.frame {
            Some(fr) => {
                if c.workplane != 0 && c.workplane != fr.h {
                    return skip(format!(
                        "{name} ({}) is stated in workplane {}, not in the sketch's workplane {}",
                        c.ty,
                        eid(c.workplane),
                        eid(fr.h)
                    ));
                }
                let projected = c.workplane == fr.h && ct::uses_workplane(c.ty);
                let projection_safe = matches!(
                    c.ty,
                    ct::DIAMETER | ct::EQUAL_RADIUS | ct::PT_ON_CIRCLE | ct::PROJ_PT_DISTANCE
                );
                Ok(!projected && !projection_safe)
            }
            None => {
                if c.workplane != 0 && ct::uses_workplane(c.ty) {
                    return skip(format!(
                        "{name} ({}) is stated in workplane {} inside a 3D sketch: the IR has no \
                         constraints projected into a plane",
                        c.ty,
                        eid(c.workplane)
                    ));
                }
                Ok(false)
            }
        }
    }

    fn value(&self, c: &Constraint) -> R<Number> {
        match &c.val_a {
            Some(v) => Ok(v.clone()),
            None => skip(format!("{} ({}) has a non-finite value", ct::name(c.ty), c.ty)),
        }
    }

    /// One constraint other than a tangency.
    fn constraint(&mut self, c: &Constraint, in_plane: bool) -> R<ir::Constraint> {
        let mut r = Refs::default();
        let abs = |n: Number| Number(n.0.abs());
        let (kind, value) = match c.ty {
            ct::POINTS_COINCIDENT => {
                r.add(self.point(c.pt_a, "ptA")?);
                r.add(self.point(c.pt_b, "ptB")?);
                (Kind::Coincident, None)
            }
            ct::PT_PT_DISTANCE => {
                r.add(self.point(c.pt_a, "ptA")?);
                r.add(self.point(c.pt_b, "ptB")?);
                (Kind::Distance, Some(self.value(c)?))
            }
            ct::PT_PLANE_DISTANCE | ct::PT_FACE_DISTANCE => {
                r.add(self.point(c.pt_a, "ptA")?);
                r.add(self.plane(c.entity_a, "entityA", true)?);
                (Kind::Distance, Some(abs(self.value(c)?)))
            }
            ct::PT_LINE_DISTANCE => {
                r.add(self.point(c.pt_a, "ptA")?);
                r.add(self.segment(c.entity_a, "entityA")?);
                (Kind::Distance, Some(abs(self.value(c)?)))
            }
            ct::PROJ_PT_DISTANCE => {
                r.add(self.point(c.pt_a, "ptA")?);
                r.add(self.point(c.pt_b, "ptB")?);
                let (kind, sign) = self.projection_axis(c.entity_a)?;
                let v = self.value(c)?;
                (kind, Some(if sign { v } else { Number(-v.0) }))
            }
            ct::PT_IN_PLANE | ct::PT_ON_FACE => {
                r.add(self.point(c.pt_a, "ptA")?);
                r.add(self.plane(c.entity_a, "entityA", false)?);
                (Kind::PointOnObject, None)
            }
            ct::PT_ON_LINE => {
                r.add(self.point(c.pt_a, "ptA")?);
                r.add(self.segment(c.entity_a, "entityA")?);
                (Kind::PointOnObject, None)
            }
            ct::EQUAL_LENGTH_LINES | ct::LENGTH_RATIO | ct::LENGTH_DIFFERENCE => {
                r.add(self.segment(c.entity_a, "entityA")?);
                r.add(self.segment(c.entity_b, "entityB")?);
                match c.ty {
                    ct::EQUAL_LENGTH_LINES => (Kind::Equal, None),
                    ct::LENGTH_RATIO => (Kind::LengthRatio, Some(self.value(c)?)),
                    _ => (Kind::LengthDifference, Some(self.value(c)?)),
                }
            }
            ct::EQ_LEN_PT_LINE_D => {
                r.add(self.segment(c.entity_a, "entityA")?);
                r.add(self.point(c.pt_a, "ptA")?);
                r.add(self.segment(c.entity_b, "entityB")?);
                (Kind::EqualLengthPointLineDistance, None)
            }
            ct::EQ_PT_LN_DISTANCES => {
                r.add(self.point(c.pt_a, "ptA")?);
                r.add(self.segment(c.entity_a, "entityA")?);
                r.add(self.point(c.pt_b, "ptB")?);
                r.add(self.segment(c.entity_b, "entityB")?);
                (Kind::EqualPointLineDistances, None)
            }
            ct::EQUAL_ANGLE => {
                // (`other=1`, the supplementary form, needs nothing more: the model's
                // EqualAngle holds for either of the two supplementary angles.)
                r.add(self.vector(c.entity_a, "entityA")?);
                r.add(self.vector(c.entity_b, "entityB")?);
                r.add(self.vector(c.entity_c, "entityC")?);
                r.add(self.vector(c.entity_d, "entityD")?);
                (Kind::EqualAngle, None)
            }
            ct::EQUAL_LINE_ARC_LEN => {
                r.add(self.segment(c.entity_a, "entityA")?);
                r.add(self.circle(c.entity_b, "entityB", true)?);
                (Kind::EqualLineArcLength, None)
            }
            ct::SYMMETRIC => {
                if self.frame.is_none() {
                    return skip(format!("SYMMETRIC (60) about a plane in 3D: {GAP_PLANE_3D}"));
                }
                r.add(self.point(c.pt_a, "ptA")?);
                r.add(self.point(c.pt_b, "ptB")?);
                r.add(self.plane(c.entity_a, "entityA", c.workplane == 0)?);
                (Kind::Symmetric, None)
            }
            ct::SYMMETRIC_HORIZ | ct::SYMMETRIC_VERT => {
                r.add(self.point(c.pt_a, "ptA")?);
                r.add(self.point(c.pt_b, "ptB")?);
                // Horizontal symmetry mirrors about the vertical axis (u = 0), and vice versa.
                r.add(self.axis(if c.ty == ct::SYMMETRIC_HORIZ { 'v' } else { 'u' })?);
                (Kind::Symmetric, None)
            }
            ct::SYMMETRIC_LINE => {
                r.add(self.point(c.pt_a, "ptA")?);
                r.add(self.point(c.pt_b, "ptB")?);
                r.add(self.segment(c.entity_a, "entityA")?);
                (Kind::Symmetric, None)
            }
            ct::AT_MIDPOINT => {
                if c.pt_a == 0 {
                    return skip(
                        "AT_MIDPOINT (70) of a segment on a plane: the IR's Midpoint takes a \
                         point, not a plane",
                    );
                }
                r.add(self.point(c.pt_a, "ptA")?);
                r.add(self.segment(c.entity_a, "entityA")?);
                (Kind::Midpoint, None)
            }
            ct::HORIZONTAL | ct::VERTICAL => {
                if c.entity_a != 0 {
                    r.add(self.segment(c.entity_a, "entityA")?);
                } else {
                    r.add(self.point(c.pt_a, "ptA")?);
                    r.add(self.point(c.pt_b, "ptB")?);
                }
                (if c.ty == ct::HORIZONTAL { Kind::Horizontal } else { Kind::Vertical }, None)
            }
            ct::DIAMETER => {
                r.add(self.circle(c.entity_a, "entityA", false)?);
                (Kind::Diameter, Some(self.value(c)?))
            }
            ct::PT_ON_CIRCLE => {
                r.add(self.point(c.pt_a, "ptA")?);
                r.add(self.circle(c.entity_a, "entityA", false)?);
                (Kind::PointOnObject, None)
            }
            ct::EQUAL_RADIUS => {
                r.add(self.circle(c.entity_a, "entityA", false)?);
                r.add(self.circle(c.entity_b, "entityB", false)?);
                (Kind::Equal, None)
            }
            ct::SAME_ORIENTATION => {
                return skip(
                    "SAME_ORIENTATION (110): two normals (orientations) aligned; the IR has no \
                     orientation entity",
                );
            }
            ct::ANGLE => {
                r.add(self.vector(c.entity_a, "entityA")?);
                r.add(self.vector(c.entity_b, "entityB")?);
                let v = self.value(c)?;
                let mut theta =
                    if c.other { Number(BigRational::from_integer(180.into()) - v.0) } else { v };
                if self.oriented_clockwise(&r.refs[0].entity, &r.refs[1].entity) {
                    theta = Number(-theta.0);
                }
                (Kind::Angle, Some(theta))
            }
            ct::PARALLEL | ct::PERPENDICULAR => {
                r.add(self.vector(c.entity_a, "entityA")?);
                r.add(self.vector(c.entity_b, "entityB")?);
                (if c.ty == ct::PARALLEL { Kind::Parallel } else { Kind::Perpendicular }, None)
            }
            ct::WHERE_DRAGGED => {
                r.add(self.point(c.pt_a, "ptA")?);
                (Kind::Fix, None)
            }
            ct::ARC_ARC_LEN_RATIO
            | ct::ARC_LINE_LEN_RATIO
            | ct::ARC_ARC_DIFFERENCE
            | ct::ARC_LINE_DIFFERENCE => {
                return skip(format!(
                    "{} ({}): a ratio or difference of arc lengths; the IR's LengthRatio and \
                     LengthDifference take segments only",
                    ct::name(c.ty),
                    c.ty
                ));
            }
            ty => return skip(format!("constraint type {ty} ({}) is not supported", ct::name(ty))),
        };
        if in_plane && let Some(id) = r.off {
            return skip(format!(
                "{} ({}) references {id}, which lies off the workplane, and the constraint is \
                 not projected into it",
                ct::name(c.ty),
                c.ty
            ));
        }
        Ok(ir::Constraint { id: cid(c.h), kind, refs: r.refs, value, driving: self.driving(c) })
    }

    /// Whether, in a 2D sketch, the second line turns clockwise from the first in the drawing
    /// (the IR's angle from the first to the second is then negative).
    fn oriented_clockwise(&self, a: &str, b: &str) -> bool {
        if self.frame.is_none() {
            return false;
        }
        let dir = |id: &str| -> Option<[f64; 2]> {
            let (p, q) = match self.geometry_by_id(id)? {
                Geometry::Segment { start, end } => (start, end),
                Geometry::Line { a, b } => (a, b),
                _ => return None,
            };
            if p.len() != 2 || q.len() != 2 {
                return None;
            }
            Some([q[0].to_f64() - p[0].to_f64(), q[1].to_f64() - p[1].to_f64()])
        };
        match (dir(a), dir(b)) {
            (Some(da), Some(db)) => da[0] * db[1] - da[1] * db[0] < 0.0,
            _ => false,
        }
    }

    /// The axis of the workplane a projected distance is measured along: `DistanceX` or
    /// `DistanceY`, and whether the direction is the axis's positive one.
    fn projection_axis(&mut self, h: u32) -> R<(Kind, bool)> {
        let Some(fr) = self.frame.clone() else {
            return skip(
                "PROJ_PT_DISTANCE (34) in 3D: a distance along a direction is not an IR kind",
            );
        };
        let e = self.ent(h, "entityA")?;
        let origin = self.origin(h)?;
        let d = if e.ty == et::LINE_SEGMENT {
            if origin != Origin::External {
                return skip(format!(
                    "PROJ_PT_DISTANCE (34) along {}, a segment of this group: a distance along \
                     a moving direction is not an IR kind",
                    eid(h)
                ));
            }
            let a = self.pos3(self.ent(e.points[0], "point[0]")?)?;
            let b = self.pos3(self.ent(e.points[1], "point[1]")?)?;
            a.sub(&b)
        } else if et::is_normal(e.ty) {
            if origin == Origin::Generated || (e.ty == 3000 && origin == Origin::Own) {
                return skip(format!(
                    "PROJ_PT_DISTANCE (34) along {}, a direction that moves with this group",
                    eid(h)
                ));
            }
            self.quat(e)?.n()
        } else if et::is_face(e.ty) {
            if origin == Origin::Generated {
                return skip(self.generated(h));
            }
            match &e.act_normal {
                [_, Some(x), Some(y), Some(z)] => V3::from_numbers([x, y, z]),
                _ => return skip(format!("{} has a non-finite normal", eid(h))),
            }
        } else {
            return skip(format!(
                "entityA {} is a {}, which has no direction",
                eid(h),
                et::name(e.ty)
            ));
        };
        let near = |x: Option<f64>, t: f64| x.is_some_and(|x| (x - t).abs() <= geom::TOL);
        let du = geom::cosine(d.f64(), fr.u.f64());
        let dv = geom::cosine(d.f64(), fr.v.f64());
        if near(du, 1.0) {
            Ok((Kind::DistanceX, true))
        } else if near(du, -1.0) {
            Ok((Kind::DistanceX, false))
        } else if near(dv, 1.0) {
            Ok((Kind::DistanceY, true))
        } else if near(dv, -1.0) {
            Ok((Kind::DistanceY, false))
        } else {
            skip(format!(
                "PROJ_PT_DISTANCE (34) along {}, which is not an axis of the workplane: a \
                 distance along a direction is not an IR kind",
                eid(h)
            ))
        }
    }

    /// A tangency at end points: the `TangentAtEnds` it becomes, and the index of the
    /// coincidence it folds in.
    fn tangency(
        &mut self,
        c: &Constraint,
        cs: &[&Constraint],
        folded: &HashMap<usize, u32>,
    ) -> R<(ir::Constraint, usize)> {
        let name = ct::name(c.ty);
        let a = self.ent(c.entity_a, "entityA")?;
        let b = self.ent(c.entity_b, "entityB")?;
        // The end point of a curve that the flag selects.
        let end = |e: &Entity, other: bool| -> R<usize> {
            match e.ty {
                et::ARC_OF_CIRCLE => Ok(if other { 2 } else { 1 }),
                et::CUBIC if e.extra_points == 0 => Ok(if other { 3 } else { 0 }),
                et::CUBIC => Ok(if other {
                    usize::try_from(e.extra_points).ok().map_or(99, |x| x.saturating_add(3))
                } else {
                    0
                }),
                ty => skip(format!("{name} ({}) on {}, a {}", c.ty, eid(e.h), et::name(ty))),
            }
        };
        let line_check = |e: &Entity| -> R<()> {
            if e.ty == et::LINE_SEGMENT {
                Ok(())
            } else {
                skip(format!("{name} ({}): {} is a {}, not a line", c.ty, eid(e.h), et::name(e.ty)))
            }
        };
        let (ia, ib_candidates): (usize, Vec<usize>) = match c.ty {
            ct::ARC_LINE_TANGENT => {
                if a.ty != et::ARC_OF_CIRCLE {
                    return skip(format!("{name} (123): {} is not an arc", eid(a.h)));
                }
                line_check(b)?;
                (end(a, c.other)?, vec![0, 1])
            }
            ct::CUBIC_LINE_TANGENT => {
                if a.ty != et::CUBIC {
                    return skip(format!("{name} (124): {} is not a cubic", eid(a.h)));
                }
                line_check(b)?;
                (end(a, c.other)?, vec![0, 1])
            }
            _ => (end(a, c.other)?, vec![end(b, c.other2)?]),
        };
        let pa = a.points.get(ia).copied().unwrap_or(0);
        let joined = |k: &Constraint, p: u32, q: u32| {
            p != 0 && q != 0 && ((k.pt_a == p && k.pt_b == q) || (k.pt_a == q && k.pt_b == p))
        };
        let found = ib_candidates.iter().find_map(|&ib| {
            let pb = b.points.get(ib).copied().unwrap_or(0);
            cs.iter()
                .enumerate()
                .find(|(k, kc)| {
                    kc.ty == ct::POINTS_COINCIDENT && !folded.contains_key(k) && joined(kc, pa, pb)
                })
                .map(|(k, _)| (ib, k))
        });
        let Some((ib, k)) = found else {
            return skip(format!(
                "{name} ({}) with no POINTS_COINCIDENT in this group joining the end points of \
                 {} and {}: SolveSpace's tangency there only aligns the directions, which no IR \
                 kind says",
                c.ty,
                eid(a.h),
                eid(b.h)
            ));
        };
        let mut refs = Vec::new();
        for (e, i) in [(a, ia), (b, ib)] {
            let Some((id, swapped)) = self.ensure_curve(e)? else {
                return skip(format!(
                    "{name} ({}): {} cannot be drawn in this sketch",
                    c.ty,
                    eid(e.h)
                ));
            };
            let Some(part) = part_of(e, i, swapped) else {
                return skip(format!("{name} ({}): {} has no end point {i}", c.ty, eid(e.h)));
            };
            refs.push(Ref::part(id, part));
        }
        let constraint = ir::Constraint {
            id: cid(c.h),
            kind: Kind::TangentAtEnds,
            refs,
            value: None,
            driving: self.driving(c),
        };
        Ok((constraint, k))
    }
}
