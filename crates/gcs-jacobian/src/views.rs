//! The views of entities that equations are written against: a point, a 2D line `(a, b, c)`,
//! its normal, a 3D line in Plücker coordinates, a plane, a circle or sphere `(centre,
//! radius)`, a segment's end points — as dual numbers over the local unknowns of one
//! constraint. A composite entity (a segment) is seen through its parts: its line is the line
//! through its two points.

use gcs_model::{EntityIdx, System};
use gcs_rank::Field;

use crate::dual::{Dual, vec as v};
use crate::layout::Layout;

/// The dual-number views of the entities bound by one constraint.
pub(crate) struct Local<'a, F> {
    system: &'a System,
    /// `(entity, its coordinates as variables)` for the base entities.
    vars: Vec<(EntityIdx, Vec<Dual<F>>)>,
    /// Local variable index → global column.
    pub(crate) cols: Vec<usize>,
    /// Whether each base entity's coordinates are homogeneous, in `vars` order.
    homogeneous: Vec<bool>,
    /// 2D lines and segments seen through a known direction ([`Local::with_lines`]).
    known: Vec<KnownLine<F>>,
}

/// A 2D line or segment not placed yet whose direction is known (the constructive placement):
/// its normal, and for a segment one of its end points that the constraint may read (its line
/// is then the line through that point with that normal).
#[derive(Clone, Debug)]
pub(crate) struct KnownLine<F> {
    /// The line or segment.
    pub(crate) line: EntityIdx,
    /// Its normal `(a, b)`.
    pub(crate) normal: [F; 2],
    /// For a segment whose position is read: the end point it goes through.
    pub(crate) anchor: Option<EntityIdx>,
}

impl<'a, F: Field> Local<'a, F> {
    /// Variables for the base entities `entities` (no segments) at `witness` (indexed by global
    /// column).
    pub(crate) fn new(
        system: &'a System,
        layout: &Layout,
        entities: &[EntityIdx],
        witness: &[F],
    ) -> Local<'a, F> {
        let cols: Vec<usize> = entities.iter().flat_map(|e| layout.columns(*e)).collect();
        let mut next = 0;
        Local::build(system, layout, entities, witness, cols, |_| {
            next += 1;
            Some(next - 1)
        })
    }

    /// The same with only the columns `vars` as variables (local variable `i` is column
    /// `vars[i]`) and every other coordinate a constant; with no `vars`, the values alone.
    /// Every value, and every derivative with respect to a column of `vars`, is the one
    /// [`Local::new`] gives: dual arithmetic computes each derivative on its own, from the
    /// values and the same derivative of the operands — at the cost of those columns only.
    pub(crate) fn over(
        system: &'a System,
        layout: &Layout,
        entities: &[EntityIdx],
        witness: &[F],
        vars: &[usize],
    ) -> Local<'a, F> {
        Local::build(system, layout, entities, witness, vars.to_vec(), |col| {
            vars.iter().position(|c| *c == col)
        })
    }

    /// The views of `entities` at `witness`, with column `col` the local variable `var(col)`
    /// (of `cols.len()`) or a constant.
    fn build(
        system: &'a System,
        layout: &Layout,
        entities: &[EntityIdx],
        witness: &[F],
        cols: Vec<usize>,
        mut var: impl FnMut(usize) -> Option<usize>,
    ) -> Local<'a, F> {
        let n = cols.len();
        let mut vars = Vec::with_capacity(entities.len());
        let homogeneous =
            entities.iter().map(|e| layout.repr(*e).is_some_and(|r| r.homogeneous())).collect();
        for &e in entities {
            let ev = layout
                .columns(e)
                .map(|col| match var(col) {
                    Some(i) => Dual::variable(witness[col].clone(), i, n),
                    None => Dual::constant(witness[col].clone()),
                })
                .collect();
            vars.push((e, ev));
        }
        Local { system, vars, cols, homogeneous, known: Vec::new() }
    }

    /// The same, with some 2D lines or segments seen through a known direction: their normal
    /// ([`Local::normal2`]) is the given one, a constant, and the line of a segment with an
    /// anchor ([`Local::line2`]) is the line through the anchor with that normal — what the
    /// constructive placement uses before the segment's other end is placed.
    pub(crate) fn with_lines(mut self, known: Vec<KnownLine<F>>) -> Self {
        self.known = known;
        self
    }

    fn known(&self, e: EntityIdx) -> Option<&KnownLine<F>> {
        self.known.iter().find(|k| k.line == e)
    }

    /// The system.
    pub(crate) fn system(&self) -> &'a System {
        self.system
    }

    /// Whether the system is spatial.
    pub(crate) fn is_3d(&self) -> bool {
        self.system.dim() == gcs_model::Dim::Three
    }

    /// Whether the coordinates of base entity `e` are homogeneous.
    pub(crate) fn homogeneous(&self, e: EntityIdx) -> bool {
        self.vars.iter().position(|(x, _)| *x == e).is_some_and(|i| self.homogeneous[i])
    }

    pub(crate) fn nvars(&self) -> usize {
        self.cols.len()
    }

    pub(crate) fn coords(&self, e: EntityIdx) -> &[Dual<F>] {
        self.vars.iter().find(|(x, _)| *x == e).map(|(_, c)| c.as_slice()).unwrap_or(&[])
    }

    pub(crate) fn point(&self, e: EntityIdx) -> Vec<Dual<F>> {
        self.coords(e).to_vec()
    }

    /// A 2D line or segment as homogeneous `(a, b, c)`.
    pub(crate) fn line2(&self, e: EntityIdx) -> [Dual<F>; 3] {
        if let Some(KnownLine { normal: [a, b], anchor: Some(p), .. }) = self.known(e) {
            let x = self.coords(*p);
            let (a, b) = (Dual::constant(a.clone()), Dual::constant(b.clone()));
            let c = match x {
                [x0, x1, ..] => -&(&(&a * x0) + &(&b * x1)),
                _ => Dual::constant(F::zero()),
            };
            return [a, b, c];
        }
        match self.system.segment_points(e) {
            Some((p, q)) => {
                let (p, q) = (self.coords(p), self.coords(q));
                // The line through p and q: (p.y − q.y) x + (q.x − p.x) y + (p.x q.y − q.x p.y).
                [&p[1] - &q[1], &q[0] - &p[0], v::cross2(p, q)]
            }
            None => {
                let c = self.coords(e);
                [c[0].clone(), c[1].clone(), c[2].clone()]
            }
        }
    }

    /// The normal `(a, b)` of a 2D line or segment (without computing its offset).
    pub(crate) fn normal2(&self, e: EntityIdx) -> [Dual<F>; 2] {
        if let Some(k) = self.known(e) {
            return [Dual::constant(k.normal[0].clone()), Dual::constant(k.normal[1].clone())];
        }
        match self.system.segment_points(e) {
            Some((p, q)) => {
                let (p, q) = (self.coords(p), self.coords(q));
                [&p[1] - &q[1], &q[0] - &p[0]]
            }
            None => {
                let c = self.coords(e);
                [c[0].clone(), c[1].clone()]
            }
        }
    }

    /// The direction `d` of a 3D line or segment (without computing its moment).
    pub(crate) fn direction3(&self, e: EntityIdx) -> Vec<Dual<F>> {
        match self.system.segment_points(e) {
            Some((p, q)) => v::sub(self.coords(q), self.coords(p)),
            None => self.coords(e)[0..3].to_vec(),
        }
    }

    /// A 3D line or segment in Plücker coordinates `(d, m)`.
    pub(crate) fn line3(&self, e: EntityIdx) -> (Vec<Dual<F>>, Vec<Dual<F>>) {
        match self.system.segment_points(e) {
            Some((p, q)) => {
                let (p, q) = (self.coords(p), self.coords(q));
                (v::sub(q, p), v::cross3(p, q))
            }
            None => {
                let c = self.coords(e);
                (c[0..3].to_vec(), c[3..6].to_vec())
            }
        }
    }

    /// A plane as `(normal, offset)`.
    pub(crate) fn plane(&self, e: EntityIdx) -> (Vec<Dual<F>>, Dual<F>) {
        let c = self.coords(e);
        (c[0..3].to_vec(), c[3].clone())
    }

    /// A circle or sphere as `(centre, radius)`.
    pub(crate) fn round(&self, e: EntityIdx) -> (Vec<Dual<F>>, Dual<F>) {
        let c = self.coords(e);
        let n = c.len() - 1;
        (c[..n].to_vec(), c[n].clone())
    }

    /// The endpoints of a segment.
    pub(crate) fn segment(&self, e: EntityIdx) -> (Vec<Dual<F>>, Vec<Dual<F>>) {
        let (p, q) = self.system.segment_points(e).unwrap_or((e, e));
        (self.point(p), self.point(q))
    }
}
