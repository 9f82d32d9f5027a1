//! Maximal rigid subsystems (witness paper §4): the clusters.
//!
//! A set of entities is *rigid* when every motion the constraints allow moves it as a whole:
//! restricted to its coordinates, every vector of `ker J` is a displacement. A *cluster* is a
//! maximal rigid set.
//!
//! # How (Algorithm 1 of the paper, with the pivot exchanges of Algorithm 2)
//!
//! *Anchoring a reference* `R` — coordinates of the set whose displacements they pin, as many as
//! the set's degree of rigidity `d = rank(T|S)` — means making `R`'s columns free in the
//! reduced row echelon form of the Jacobian ([`gcs_rank::Echelon::make_free`], a pivot
//! exchange per column, not a new elimination). A column is then *determined by `R`* when its
//! row involves no other free column: whatever the motion, once `R` is held, it does not move.
//! A set `S` is rigid exactly when, for such an `R ⊆ S`, every column of `S` is in `R` or
//! determined by it; and the cluster of a rigid `S` is everything determined by `R`, extended
//! one entity at a time while the degree of rigidity grows (a bar in 3D, with `d = 5`, grows to
//! a triangle with `d = 6`), until no entity can join.
//!
//! *Absolute constraints* (`Fix`, `Horizontal`, `Vertical`) are not invariant under
//! displacements. They are rewritten as relations to a *frame*, a virtual object whose `k`
//! coordinates (3 in 2D, 6 in 3D) are a displacement of the ambient space: in the augmented
//! Jacobian `[J | −J_abs·T]` every displacement is admitted, and the entities held by absolute
//! constraints join the frame's cluster (the frame is never reported). See the proof sketch in
//! [`Subsystem`]'s docs.
//!
//! Seeds are the constraints in file order: the entities of a constraint not yet inside one
//! cluster, when rigid, grow into the cluster that contains them. Entities in no cluster at the
//! end get a cluster of their own.

use std::collections::HashMap;

use gcs_jacobian::{Jacobian, Layout, RowOwner};
use gcs_model::{ConstraintIdx, EntityIdx, System};
use gcs_rank::{Echelon, EchelonOptions, Field, SparseRow};

/// How the clusters are found. All four give the same clusters; they differ in cost.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum ClusterMethod {
    /// One elimination; every question ("is this set rigid?", "what does anchoring it hold?")
    /// is then answered in the small space of the free columns: the velocity of a column is
    /// minus its reduced row over the free columns (the kernel restricted to it). No pivot
    /// exchange, no new elimination.
    Kernel,
    /// The paper's Algorithm 2: one elimination, each reference anchored by pivot exchanges
    /// ([`gcs_rank::Echelon::make_free`]) on that echelon.
    Exchange,
    /// The paper's Algorithm 1: a new elimination for each reference, its columns ordered last.
    Eliminate,
    /// The paper's shortcut for open chains (§4: systems whose cycles all lie in rigid
    /// subsystems), done with the constraint graph: split it into biconnected blocks at its
    /// articulation entities; when every block is rigid by itself the clusters are the
    /// blocks, found by one small elimination per block and none of the whole system. Falls
    /// back to [`ClusterMethod::Kernel`] where it does not apply (see `open_chain`'s docs
    /// for the conditions, each checked exactly at the witness; with floats it never applies).
    /// Where it does not apply it costs a block decomposition and the plain echelon rank of
    /// the blocks up to the first one that is not rigid. The default.
    #[default]
    OpenChain,
}

impl ClusterMethod {
    /// Whether the search answers its questions in the kernel (the default, and the fallback
    /// of the open-chain shortcut).
    fn uses_kernel(self) -> bool {
        matches!(self, ClusterMethod::Kernel | ClusterMethod::OpenChain)
    }
}

/// What a group of rows stands for.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub(crate) enum Label {
    /// A constraint of the system.
    Constraint(ConstraintIdx),
    /// A virtual relation (a boundary constraint), numbered by its creator.
    Virtual(usize),
}

/// The rows of one constraint (or virtual relation) at the witness.
#[derive(Clone, Debug)]
pub(crate) struct Group<F> {
    pub(crate) label: Label,
    /// The entities with DOF it binds (segments replaced by their points).
    pub(crate) entities: Vec<EntityIdx>,
    pub(crate) rows: Vec<SparseRow<F>>,
    /// Whether it is absolute (`Fix`, `Horizontal`, `Vertical`).
    pub(crate) absolute: bool,
}

/// Everything the cluster search needs about the system at the witness, in a field.
pub(crate) struct Context<'a, F> {
    pub(crate) system: &'a System,
    pub(crate) layout: &'a Layout,
    /// The displacement generators, dense over the model's columns.
    pub(crate) generators: Vec<Vec<F>>,
    /// Entity-internal rows by entity.
    pub(crate) internal: HashMap<EntityIdx, Vec<SparseRow<F>>>,
    pub(crate) options: EchelonOptions,
    /// How clusters are found.
    pub(crate) method: ClusterMethod,
    /// Whether a subsystem that is a 2D bar framework is decided by the pebble game
    /// ([`pebble_clusters`]) instead of at the witness.
    pub(crate) pebble: bool,
}

impl<'a, F: Field> Context<'a, F> {
    pub(crate) fn new(
        system: &'a System,
        layout: &'a Layout,
        jacobian: &Jacobian<F>,
        generators: Vec<Vec<F>>,
        options: EchelonOptions,
    ) -> Self {
        let mut internal: HashMap<EntityIdx, Vec<SparseRow<F>>> = HashMap::new();
        for (row, owner) in jacobian.rows.iter().zip(&jacobian.owners) {
            if let RowOwner::Internal(e) = owner {
                internal.entry(*e).or_default().push(row.clone());
            }
        }
        Context {
            system,
            layout,
            generators,
            internal,
            options,
            method: ClusterMethod::default(),
            pebble: false,
        }
    }

    /// The groups of every constraint of the system, from the Jacobian.
    pub(crate) fn constraint_groups(&self, jacobian: &Jacobian<F>) -> Vec<Group<F>> {
        let mut groups: Vec<Group<F>> = self
            .system
            .constraint_indices()
            .map(|c| Group {
                label: Label::Constraint(c),
                entities: self.system.constraint_base_entities(c),
                rows: Vec::new(),
                absolute: self.system.constraint(c).kind.is_absolute(),
            })
            .collect();
        for (row, owner) in jacobian.rows.iter().zip(&jacobian.owners) {
            if let RowOwner::Constraint(c) = owner {
                groups[c.index()].rows.push(row.clone());
            }
        }
        groups
    }

    fn k(&self) -> usize {
        self.generators.len()
    }

    /// The row of the displacement generators at model column `c`: the velocities of `c`
    /// under the `k` generators, as a sparse vector over them.
    pub(crate) fn t_row(&self, c: usize) -> SparseRow<F> {
        SparseRow::from_entries(
            self.generators
                .iter()
                .enumerate()
                .filter(|(_, t)| !t[c].is_zero())
                .map(|(j, t)| (j, t[c].clone()))
                .collect(),
        )
    }
}

/// A subsystem: entities (with DOF) and groups of rows among them.
///
/// Proof sketch of the frame construction: for an absolute row `y`, the frame columns carry
/// `−y·T_j`; relative rows are displacement-invariant (`y·T_j = 0` at a solution). So
/// `(v, ψ)` is in the kernel of the augmented Jacobian exactly when `J(v − Tψ) = 0`, i.e. the
/// projection of the augmented kernel is `ker J + span T`: the motions allowed, up to a global
/// displacement — which is what relative placement is about — and every displacement
/// `(T_j, e_j)` is in the augmented kernel.
#[derive(Clone, Debug)]
pub(crate) struct Subsystem<F> {
    pub(crate) entities: Vec<EntityIdx>,
    pub(crate) groups: Vec<Group<F>>,
}

/// A maximal rigid subsystem.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct RawCluster {
    /// Entities with DOF, in file order.
    pub(crate) entities: Vec<EntityIdx>,
    /// Indices of the subsystem's groups whose entities all lie in the cluster.
    pub(crate) groups: Vec<usize>,
    /// Whether it contains the frame (held by absolute constraints).
    pub(crate) grounded: bool,
}

/// An object of the search: an entity of the subsystem (by position) or the frame.
type Obj = usize;

struct Search<'c, 'a, F> {
    ctx: &'c Context<'a, F>,
    sub: &'c Subsystem<F>,
    echelon: Echelon<F>,
    frame: Option<Obj>,
    /// Columns of each object.
    cols: Vec<Vec<usize>>,
    /// Objects bound by each group (frame included for absolute groups).
    group_objs: Vec<Vec<Obj>>,
    /// Groups of each object.
    obj_groups: Vec<Vec<usize>>,
    /// Connected component of each object.
    component: Vec<usize>,
    ncols: usize,
    /// Scale of the frame's columns (1 with exact arithmetic).
    frame_scale: F,
    /// The rows inserted (for Algorithm 1, which eliminates again for each reference).
    rows: Vec<SparseRow<F>>,
}

impl<'c, 'a, F: Field> Search<'c, 'a, F> {
    fn new(ctx: &'c Context<'a, F>, sub: &'c Subsystem<F>) -> Self {
        let layout = ctx.layout;
        let k = ctx.k();
        let has_frame = sub.groups.iter().any(|g| g.absolute);
        let ncols = layout.ncols();
        let total = ncols + if has_frame { k } else { 0 };
        let n = sub.entities.len();
        let frame = has_frame.then_some(n);
        let mut cols: Vec<Vec<usize>> =
            sub.entities.iter().map(|e| layout.columns(*e).collect()).collect();
        if has_frame {
            cols.push((ncols..ncols + k).collect());
        }
        let pos: HashMap<EntityIdx, Obj> =
            sub.entities.iter().enumerate().map(|(i, e)| (*e, i)).collect();
        let mut group_objs = Vec::with_capacity(sub.groups.len());
        let mut obj_groups = vec![Vec::new(); cols.len()];
        for (gi, g) in sub.groups.iter().enumerate() {
            let mut objs: Vec<Obj> =
                g.entities.iter().filter_map(|e| pos.get(e).copied()).collect();
            if g.absolute {
                objs.extend(frame);
            }
            for o in &objs {
                obj_groups[*o].push(gi);
            }
            group_objs.push(objs);
        }
        // The frame's coordinates are a parametrisation of the displacements; any scale does.
        // Exact fields keep 1. With floats, threshold pivoting picks the largest entries: frame
        // columns (shared by every absolute row) would become pivots early and fill every row,
        // so they are scaled well below the model's entries (and its displacements back up).
        let frame_scale = if ctx.options.tolerance.is_some() && has_frame {
            let (mut model, mut framed) = (f64::INFINITY, 0.0f64);
            for g in sub.groups.iter().filter(|g| g.absolute) {
                for r in &g.rows {
                    let m = r.entries().iter().map(|(_, v)| v.magnitude()).fold(0.0, f64::max);
                    model = model.min(m);
                    for t in &ctx.generators {
                        framed = framed.max(r.dot_dense(t).magnitude());
                    }
                }
            }
            let s = if framed > 0.0 && model.is_finite() { 1e-3 * model / framed } else { 1.0 };
            gcs_rank::BigRational::from_float(s.clamp(1e-12, 1.0))
                .and_then(|q| F::from_rational(&q).ok())
                .unwrap_or_else(F::one)
        } else {
            F::one()
        };
        let mut rows: Vec<SparseRow<F>> = Vec::new();
        for e in &sub.entities {
            rows.extend(ctx.internal.get(e).into_iter().flatten().cloned());
        }
        for g in &sub.groups {
            for r in &g.rows {
                if g.absolute {
                    let mut entries = r.entries().to_vec();
                    for (j, t) in ctx.generators.iter().enumerate() {
                        let v = r.dot_dense(t).mul(&frame_scale);
                        if !v.is_zero() {
                            entries.push((ncols + j, v.neg()));
                        }
                    }
                    rows.push(SparseRow::from_entries(entries));
                } else {
                    rows.push(r.clone());
                }
            }
        }
        let mut echelon = Echelon::new(total, ctx.options.clone());
        for r in &rows {
            echelon.insert(r.clone());
        }
        // Connected components of the object–group graph.
        let mut component = vec![usize::MAX; cols.len()];
        let mut next = 0;
        for start in 0..cols.len() {
            if component[start] != usize::MAX {
                continue;
            }
            let mut stack = vec![start];
            component[start] = next;
            while let Some(o) = stack.pop() {
                for g in &obj_groups[o] {
                    for p in &group_objs[*g] {
                        if component[*p] == usize::MAX {
                            component[*p] = next;
                            stack.push(*p);
                        }
                    }
                }
            }
            next += 1;
        }
        Search {
            ctx,
            sub,
            echelon,
            frame,
            cols,
            group_objs,
            obj_groups,
            component,
            ncols,
            frame_scale,
            rows,
        }
    }

    /// The row of the displacement generators at column `c` (for the frame: a unit vector).
    fn t_row(&self, c: usize) -> SparseRow<F> {
        if c >= self.ncols {
            // A displacement moves the (scaled) frame coordinate by 1/scale.
            let inv = self.frame_scale.inv().unwrap_or_else(F::one);
            return SparseRow::from_entries(vec![(c - self.ncols, inv)]);
        }
        self.ctx.t_row(c)
    }

    /// A reference of a set: columns whose displacement rows are independent, as many as the
    /// set's degree of rigidity.
    fn reference(&self, set: &[Obj]) -> Vec<usize> {
        let k = self.ctx.k();
        let mut e = Echelon::new(k, self.ctx.options.clone());
        let mut r = Vec::new();
        for &o in set {
            for &c in &self.cols[o] {
                if e.rank() == k {
                    return r;
                }
                if e.insert(self.t_row(c)).is_independent() {
                    r.push(c);
                }
            }
        }
        r
    }

    /// Makes the reference's columns free; false if one cannot be (then the reference was not
    /// independent — impossible with exact arithmetic).
    fn anchor(&mut self, reference: &[usize]) -> bool {
        let keep = self.mask(reference);
        if self.ctx.method == ClusterMethod::Eliminate {
            // Algorithm 1: eliminate again with the reference's columns last.
            let n = self.echelon.ncols();
            let priority: Vec<usize> = (0..n).map(|c| if keep[c] { n + c } else { c }).collect();
            let mut e = Echelon::new(n, self.ctx.options.clone());
            e.set_priority(priority);
            for r in &self.rows {
                e.insert(r.clone());
            }
            self.echelon = e;
            return reference.iter().all(|c| !self.echelon.is_pivot(*c));
        }
        reference.iter().all(|&c| self.echelon.make_free(c, &keep).unwrap_or(false))
    }

    /// The velocity of column `c` as a linear form in the free-column parameters of the kernel:
    /// a free column is its own parameter; a pivot column is minus its reduced row (which has
    /// entries on free columns only).
    fn velocity(&self, c: usize) -> SparseRow<F> {
        match self.echelon.pivot_row(c) {
            None => SparseRow::from_entries(vec![(c, F::one())]),
            Some(row) => SparseRow::from_entries(
                row.entries()
                    .iter()
                    .filter(|(col, _)| *col != c)
                    .map(|(col, v)| (*col, v.neg()))
                    .collect(),
            ),
        }
    }

    /// Kernel method: whether a set is rigid — the velocities of its columns, as functions of
    /// the kernel parameters, stay in the span of the displacements restricted to it. Returns
    /// the set's degree of rigidity too.
    fn kernel_rigid(&self, set: &[Obj]) -> (bool, usize) {
        let cols: Vec<usize> = set.iter().flat_map(|o| self.cols[*o].iter().copied()).collect();
        let m = cols.len();
        let mut e = Echelon::new(m, self.ctx.options.clone());
        // Columns of T restricted to the set, as vectors over the set's columns.
        let k = self.ctx.k();
        let mut t_cols: Vec<Vec<(usize, F)>> = vec![Vec::new(); k];
        for (i, &c) in cols.iter().enumerate() {
            for (j, v) in self.t_row(c).entries() {
                t_cols[*j].push((i, v.clone()));
            }
        }
        for t in t_cols {
            e.insert(SparseRow::from_entries(t));
        }
        let dor = e.rank();
        // Columns of the velocity map, one per kernel parameter.
        let mut by_param: std::collections::BTreeMap<usize, Vec<(usize, F)>> = Default::default();
        for (i, &c) in cols.iter().enumerate() {
            for (f, v) in self.velocity(c).entries() {
                by_param.entry(*f).or_default().push((i, v.clone()));
            }
        }
        for (_, v) in by_param {
            if e.insert(SparseRow::from_entries(v)).is_independent() {
                return (false, dor);
            }
        }
        (true, dor)
    }

    /// Kernel method: the objects held when a rigid set of full degree of rigidity is
    /// anchored: those whose velocities are combinations of the set's (anything that vanishes
    /// on the set vanishes on them).
    fn kernel_closure_full(&self, set: &[Obj], members: &[Obj]) -> Vec<Obj> {
        let mut e = Echelon::new(self.echelon.ncols(), self.ctx.options.clone());
        for o in set {
            for c in &self.cols[*o] {
                e.insert(self.velocity(*c));
            }
        }
        members
            .iter()
            .copied()
            .filter(|o| {
                set.contains(o)
                    || self.cols[*o].iter().all(|c| e.reduce(&self.velocity(*c)).is_zero())
            })
            .collect()
    }

    /// Whether column `c` is held by the anchored reference (in it, or determined by it).
    fn held(&self, c: usize, keep: &[bool]) -> bool {
        if keep[c] {
            return true;
        }
        match self.echelon.pivot_row(c) {
            None => false,
            Some(row) => row.entries().iter().all(|(col, _)| *col == c || keep[*col]),
        }
    }

    fn obj_held(&self, o: Obj, keep: &[bool]) -> bool {
        self.cols[o].iter().all(|c| self.held(*c, keep))
    }

    fn mask(&self, reference: &[usize]) -> Vec<bool> {
        let mut keep = vec![false; self.echelon.ncols()];
        for &c in reference {
            keep[c] = true;
        }
        keep
    }

    /// Whether a set of objects is rigid.
    fn rigid(&mut self, set: &[Obj]) -> bool {
        if self.ctx.method.uses_kernel() {
            return self.kernel_rigid(set).0;
        }
        let r = self.reference(set);
        if !self.anchor(&r) {
            return false;
        }
        let keep = self.mask(&r);
        set.iter().all(|o| self.obj_held(*o, &keep))
    }

    /// The maximal rigid set containing the rigid set `seed`.
    fn grow(&mut self, seed: Vec<Obj>) -> Vec<Obj> {
        let k = self.ctx.k();
        let comp = self.component[seed[0]];
        let members: Vec<Obj> =
            (0..self.cols.len()).filter(|o| self.component[*o] == comp).collect();
        let mut set = seed;
        loop {
            let (mut closure, d) = if self.ctx.method.uses_kernel() {
                let (_, d) = self.kernel_rigid(&set);
                if d == k {
                    (self.kernel_closure_full(&set, &members), d)
                } else {
                    // Low degree of rigidity: the objects that join without raising it.
                    let c: Vec<Obj> = members
                        .iter()
                        .copied()
                        .filter(|o| {
                            if set.contains(o) {
                                return true;
                            }
                            let mut bigger = set.clone();
                            bigger.push(*o);
                            self.kernel_rigid(&bigger) == (true, d)
                        })
                        .collect();
                    (c, d)
                }
            } else {
                let r = self.reference(&set);
                self.anchor(&r);
                let keep = self.mask(&r);
                let c = members
                    .iter()
                    .copied()
                    .filter(|o| set.contains(o) || self.obj_held(*o, &keep))
                    .collect();
                (c, r.len())
            };
            closure.sort_unstable();
            if d == k {
                return closure;
            }
            // The degree of rigidity is not full: try to extend by one entity (neighbours
            // first); an extension raises it, so this loops at most k times.
            let mut inside = vec![false; self.cols.len()];
            for o in &closure {
                inside[*o] = true;
            }
            let mut neighbours: Vec<Obj> = Vec::new();
            for o in &closure {
                for g in &self.obj_groups[*o] {
                    for p in &self.group_objs[*g] {
                        if !inside[*p] && !neighbours.contains(p) {
                            neighbours.push(*p);
                        }
                    }
                }
            }
            let others = members.iter().copied().filter(|o| !inside[*o] && !neighbours.contains(o));
            let candidates: Vec<Obj> = neighbours.iter().copied().chain(others).collect();
            let mut extended = None;
            for e in candidates {
                let mut bigger = closure.clone();
                bigger.push(e);
                if self.rigid(&bigger) {
                    extended = Some(bigger);
                    break;
                }
            }
            match extended {
                Some(b) => set = b,
                None => return closure,
            }
        }
    }

    fn run(mut self) -> Vec<RawCluster> {
        let nobj = self.cols.len();
        let mut clusters: Vec<Vec<Obj>> = Vec::new();
        let mut of_obj: Vec<Vec<usize>> = vec![Vec::new(); nobj];
        let covered = |objs: &[Obj], of_obj: &[Vec<usize>]| -> bool {
            let Some(first) = objs.first() else { return true };
            of_obj[*first].iter().any(|c| objs.iter().all(|o| of_obj[*o].contains(c)))
        };
        for gi in 0..self.sub.groups.len() {
            let objs = self.group_objs[gi].clone();
            if objs.is_empty() || covered(&objs, &of_obj) {
                continue;
            }
            if !self.rigid(&objs) {
                continue;
            }
            let cluster = self.grow(objs);
            if clusters.contains(&cluster) {
                continue;
            }
            for o in &cluster {
                of_obj[*o].push(clusters.len());
            }
            clusters.push(cluster);
        }
        for (o, of) in of_obj.iter_mut().enumerate() {
            if of.is_empty() && Some(o) != self.frame {
                of.push(clusters.len());
                clusters.push(vec![o]);
            }
        }
        let frame = self.frame;
        // Groups of each cluster: those whose objects are all in it (found through the short
        // per-object cluster lists, not by scanning every cluster).
        let mut groups_of: Vec<Vec<usize>> = vec![Vec::new(); clusters.len()];
        for (g, objs) in self.group_objs.iter().enumerate() {
            let Some(first) = objs.first() else { continue };
            for &c in &of_obj[*first] {
                if objs.iter().all(|o| of_obj[*o].contains(&c)) {
                    groups_of[c].push(g);
                }
            }
        }
        clusters
            .into_iter()
            .zip(groups_of)
            .filter(|(c, _)| c.iter().any(|o| Some(*o) != frame))
            .map(|(c, groups)| {
                let mut entities: Vec<EntityIdx> = c
                    .iter()
                    .filter(|o| Some(**o) != frame)
                    .map(|o| self.sub.entities[*o])
                    .collect();
                entities.sort_unstable();
                RawCluster { entities, groups, grounded: frame.is_some_and(|f| c.contains(&f)) }
            })
            .collect()
    }
}

/// The maximal rigid subsystems of a subsystem, sorted by first entity (file order).
pub(crate) fn clusters<F: Field>(ctx: &Context<'_, F>, sub: &Subsystem<F>) -> Vec<RawCluster> {
    if ctx.pebble
        && let Some(out) = pebble_clusters(ctx, sub)
    {
        return out;
    }
    if ctx.method == ClusterMethod::OpenChain
        && let Some(mut out) = open_chain(ctx, sub)
    {
        out.sort_by(|a, b| a.entities.cmp(&b.entities));
        return out;
    }
    let mut out = Search::new(ctx, sub).run();
    out.sort_by(|a, b| a.entities.cmp(&b.entities));
    out
}

/// The maximal rigid subsystems of a 2D bar framework — points, and groups that are each one
/// distance between two of them (a constraint's, or a boundary's virtual one) — by the (2,3)
/// pebble game ([`crate::pebble_game`]), sorted as [`clusters`] sorts them; `None` when `sub`
/// is not such a framework.
///
/// By Laman's theorem the game's components are the generic clusters, which the witness's are
/// (the witness analysis's own premise); at a special witness they can differ, and the game's
/// are then the right ones (a point sketched on a hinge is not in both bodies' clusters
/// generically). Cross-checked against [`Search`] on random frameworks in the tests.
fn pebble_clusters<F>(ctx: &Context<'_, F>, sub: &Subsystem<F>) -> Option<Vec<RawCluster>> {
    let bars = bar_framework(ctx, sub)?;
    let game = crate::pebble_game(sub.entities.len(), &bars);
    Some(bar_clusters(sub, &bars, &game.components))
}

/// The clusters of a 2D bar framework (`bars`: [`bar_framework`]) from the pebble game's
/// maximal rigid components of it, sorted as [`clusters`] sorts them.
pub(crate) fn bar_clusters<F>(
    sub: &Subsystem<F>,
    bars: &[(usize, usize)],
    components: &[Vec<usize>],
) -> Vec<RawCluster> {
    // Each bar lies in exactly one component: the one of its first end that holds the other.
    let mut of_vertex: Vec<Vec<usize>> = vec![Vec::new(); sub.entities.len()];
    for (k, c) in components.iter().enumerate() {
        for &v in c {
            of_vertex[v].push(k);
        }
    }
    let mut groups: Vec<Vec<usize>> = vec![Vec::new(); components.len()];
    for (g, &(u, v)) in bars.iter().enumerate() {
        if let Some(&k) = of_vertex[u].iter().find(|k| components[**k].binary_search(&v).is_ok()) {
            groups[k].push(g);
        }
    }
    let mut out: Vec<RawCluster> = components
        .iter()
        .zip(groups)
        .map(|(c, groups)| {
            let mut entities: Vec<EntityIdx> = c.iter().map(|&v| sub.entities[v]).collect();
            entities.sort_unstable();
            RawCluster { entities, groups, grounded: false }
        })
        .collect();
    out.sort_by(|a, b| a.entities.cmp(&b.entities));
    out
}

/// The bars of a subsystem that is a 2D bar framework (see [`pebble_clusters`]), group by
/// group, as pairs of positions in `sub.entities`; `None` when it is not one.
pub(crate) fn bar_framework<F>(
    ctx: &Context<'_, F>,
    sub: &Subsystem<F>,
) -> Option<Vec<(usize, usize)>> {
    use gcs_model::{Dim, EntityKind, Metric, Signature};
    let system = ctx.system;
    if system.dim() != Dim::Two
        || sub.entities.iter().any(|e| system.entity(*e).kind() != EntityKind::Point)
    {
        return None;
    }
    let vertex: HashMap<EntityIdx, usize> =
        sub.entities.iter().enumerate().map(|(i, e)| (*e, i)).collect();
    let mut bars = Vec::with_capacity(sub.groups.len());
    for g in &sub.groups {
        let distance = match g.label {
            Label::Constraint(c) => matches!(
                system.constraint(c).signature,
                Signature::Metric(Metric::DistancePointPoint(..))
            ),
            // Between two points, a boundary relation is a distance (see `wdec::relations`).
            Label::Virtual(_) => true,
        };
        let [a, b] = g.entities[..] else { return None };
        if !distance || g.absolute || g.rows.len() != 1 || a == b {
            return None;
        }
        bars.push((*vertex.get(&a)?, *vertex.get(&b)?));
    }
    Some(bars)
}

/// The open-chain shortcut (witness paper §4, after Algorithm 2), or `None` where it does not
/// apply.
///
/// The entity graph (two entities adjacent when a group binds both) is split into biconnected
/// blocks; an *articulation* is an entity in several blocks. The clusters are the blocks when:
///
/// 1. no group is absolute (no frame);
/// 2. the entities of every group have full degree of rigidity (`rank T = k` on them: in 2D
///    two distinct points, a point and a line; not a single entity, parallel lines, coincident
///    points, nor a bar in 3D);
/// 3. every articulation `h` is a point, line or plane in the sense that its degree of
///    rigidity equals its DOF (`rank T|h = DOF(h)`): every velocity of `h` is then that of a
///    displacement;
/// 4. every block `B` of two or more entities is rigid by itself with full degree of
///    rigidity: `rank T|B = k` and its rows (its groups and its entities' internal rows) have
///    rank `cols(B) − k`;
/// 5. no entity `y ≠ h` of the component is left fixed by the whole stabiliser of an
///    articulation `h` (the displacements that do not move `h`).
///
/// Why: by 3, a motion of a block alone extends to the whole system (each part hanging from
/// the block at an articulation `h` follows the displacement that moves `h` as the block
/// does), so by 4 each block is rigid in the whole. The general search grows a cluster from
/// each group whose entities are not yet in one cluster; such a seed lies in a block `B`, so
/// it is rigid, and by 2 its degree of rigidity is full: its cluster is every entity it holds
/// (whose velocity vanishes whenever the seed's does). That is all of `B`, which is rigid and
/// contains it, and nothing beyond an articulation `h` of `B`: applying any `g` of the
/// stabiliser of `h` to the side of `h` away from `B` keeps every constraint and fixes the
/// seed, and by 5 each entity there is moved by some `g`. So the clusters are the blocks, and
/// entities in no block (bound by no group) are clusters of their own. Without 2, the search
/// grows low-rigidity seeds entity by entity, and at special positions such growth can reach
/// across an articulation whose stabiliser each side pins only in part (a 3D line hinge: a
/// point on it stops the turn about it, a plane through it the slide along it).
///
/// Exact fields only (with floats, the kernel method decides). Cost: a linear block
/// decomposition, one plain echelon rank per block, and for each articulation a check of the
/// entities of its component against its stabiliser — no elimination of the whole system.
pub(crate) fn open_chain<F: Field>(
    ctx: &Context<'_, F>,
    sub: &Subsystem<F>,
) -> Option<Vec<RawCluster>> {
    // Condition 5 asks for exact zeros: not with floats.
    if !F::EXACT || ctx.options.tolerance.is_some() || sub.groups.iter().any(|g| g.absolute) {
        return None;
    }
    let n = sub.entities.len();
    let pos: HashMap<EntityIdx, usize> =
        sub.entities.iter().enumerate().map(|(i, e)| (*e, i)).collect();
    let members: Vec<Vec<usize>> = sub
        .groups
        .iter()
        .map(|g| {
            let mut m: Vec<usize> = g.entities.iter().filter_map(|e| pos.get(e).copied()).collect();
            m.sort_unstable();
            m.dedup();
            m
        })
        .collect();
    let mut adj: Vec<Vec<usize>> = vec![Vec::new(); n];
    for m in &members {
        for (i, &a) in m.iter().enumerate() {
            for &b in &m[i + 1..] {
                adj[a].push(b);
                adj[b].push(a);
            }
        }
    }
    for a in &mut adj {
        a.sort_unstable();
        a.dedup();
    }
    let (blocks, component) = biconnected_blocks(&adj);
    let mut blocks_of: Vec<Vec<usize>> = vec![Vec::new(); n];
    for (b, block) in blocks.iter().enumerate() {
        for &v in block {
            blocks_of[v].push(b);
        }
    }
    // Groups of each block. A group of one entity fails condition 2 (a single entity never
    // has full degree of rigidity), so every group here binds two or more, all in one block.
    let mut groups_of: Vec<Vec<usize>> = vec![Vec::new(); blocks.len()];
    for (g, m) in members.iter().enumerate() {
        let Some(&first) = m.first() else { continue };
        if m.len() == 1 {
            return None;
        }
        let b = blocks_of[first]
            .iter()
            .copied()
            .find(|b| m.iter().all(|v| blocks_of[*v].contains(b)))?;
        groups_of[b].push(g);
    }
    let k = ctx.k();
    let cols: Vec<Vec<usize>> =
        sub.entities.iter().map(|e| ctx.layout.columns(*e).collect()).collect();
    let displacements = |set: &[usize]| -> Echelon<F> {
        let mut e = Echelon::new(k, ctx.options.clone());
        for &v in set {
            for &c in &cols[v] {
                e.insert(ctx.t_row(c));
            }
        }
        e
    };
    // Condition 2.
    if members.iter().any(|m| !m.is_empty() && displacements(m).rank() != k) {
        return None;
    }
    // Condition 3, and the stabilisers for condition 5.
    let mut stabilisers: Vec<(usize, Vec<SparseRow<F>>)> = Vec::new();
    for v in 0..n {
        if blocks_of[v].len() < 2 {
            continue;
        }
        let e = displacements(&[v]);
        let internal = ctx.internal.get(&sub.entities[v]).map_or(0, Vec::len);
        if e.rank() + internal != cols[v].len() {
            return None;
        }
        stabilisers.push((v, e.kernel_basis()));
    }
    // Condition 4.
    for (b, block) in blocks.iter().enumerate() {
        if displacements(block).rank() != k {
            return None;
        }
        let local: HashMap<usize, usize> = block
            .iter()
            .flat_map(|v| cols[*v].iter().copied())
            .enumerate()
            .map(|(i, c)| (c, i))
            .collect();
        let renumber = |r: &SparseRow<F>| -> Option<SparseRow<F>> {
            let entries: Option<Vec<(usize, F)>> =
                r.entries().iter().map(|(c, x)| local.get(c).map(|i| (*i, x.clone()))).collect();
            entries.map(SparseRow::from_entries)
        };
        let mut rows = Vec::new();
        for v in block {
            for r in ctx.internal.get(&sub.entities[*v]).into_iter().flatten() {
                rows.push(renumber(r)?);
            }
        }
        for g in &groups_of[b] {
            for r in &sub.groups[*g].rows {
                rows.push(renumber(r)?);
            }
        }
        // Fewer rows than the rank needs (a removal trial of the W-decomposition): not rigid,
        // no elimination. Otherwise, exact field (checked on entry): the plain echelon rank is
        // enough and cheap, so a large block that is not rigid costs little before the kernel
        // method takes over.
        if rows.len() + k < local.len()
            || gcs_rank::echelon_rank(local.len(), rows).0 + k != local.len()
        {
            return None;
        }
    }
    // Condition 5: the velocity of each column of `y` under each stabiliser generator `s`,
    // `Σ_j T_j[c]·s_j`, computed in place (this loop visits every entity once per
    // articulation).
    for (h, stab) in &stabilisers {
        for y in (0..n).filter(|y| y != h && component[*y] == component[*h]) {
            let fixed = cols[y].iter().all(|&c| {
                stab.iter().all(|s| {
                    let mut v = F::zero();
                    for (j, x) in s.entries() {
                        v = v.add(&ctx.generators[*j][c].mul(x));
                    }
                    v.is_zero()
                })
            });
            if fixed {
                return None;
            }
        }
    }
    let mut out: Vec<RawCluster> = blocks
        .into_iter()
        .zip(groups_of)
        .map(|(block, groups)| {
            let mut entities: Vec<EntityIdx> = block.iter().map(|v| sub.entities[*v]).collect();
            entities.sort_unstable();
            RawCluster { entities, groups, grounded: false }
        })
        .collect();
    for (v, of) in blocks_of.iter().enumerate() {
        if of.is_empty() {
            out.push(RawCluster {
                entities: vec![sub.entities[v]],
                groups: Vec::new(),
                grounded: false,
            });
        }
    }
    Some(out)
}

/// The biconnected blocks of an undirected graph (adjacency lists without duplicates; isolated
/// vertices are in no block), and the connected component of each vertex. Iterative
/// Hopcroft–Tarjan with an edge stack.
fn biconnected_blocks(adj: &[Vec<usize>]) -> (Vec<Vec<usize>>, Vec<usize>) {
    const UNSEEN: usize = usize::MAX;
    let n = adj.len();
    let mut order = vec![UNSEEN; n];
    let mut low = vec![0; n];
    let mut component = vec![UNSEEN; n];
    let mut blocks: Vec<Vec<usize>> = Vec::new();
    let mut edges: Vec<(usize, usize)> = Vec::new();
    let mut time = 0;
    for root in 0..n {
        if order[root] != UNSEEN {
            continue;
        }
        order[root] = time;
        low[root] = time;
        time += 1;
        component[root] = root;
        // (vertex, parent, next neighbour index)
        let mut stack: Vec<(usize, usize, usize)> = vec![(root, UNSEEN, 0)];
        while let Some(&mut (v, parent, ref mut next)) = stack.last_mut() {
            if *next < adj[v].len() {
                let w = adj[v][*next];
                *next += 1;
                if order[w] == UNSEEN {
                    order[w] = time;
                    low[w] = time;
                    time += 1;
                    component[w] = root;
                    edges.push((v, w));
                    stack.push((w, v, 0));
                } else if w != parent && order[w] < order[v] {
                    edges.push((v, w));
                    low[v] = low[v].min(order[w]);
                }
                continue;
            }
            stack.pop();
            let Some(&(u, _, _)) = stack.last() else { continue };
            low[u] = low[u].min(low[v]);
            if low[v] >= order[u] {
                // `u` separates the block of the edge (u, v): pop it.
                let mut block: Vec<usize> = Vec::new();
                while let Some((a, b)) = edges.pop() {
                    block.push(a);
                    block.push(b);
                    if (a, b) == (u, v) {
                        break;
                    }
                }
                block.sort_unstable();
                block.dedup();
                blocks.push(block);
            }
        }
    }
    (blocks, component)
}
