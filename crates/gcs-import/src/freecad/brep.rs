//! A reader of the subset of OpenCASCADE's text BRep format (`CASCADE Topology V1`–`V3`) that
//! resolving a sketch's external geometry needs: the shape's topology (to number its edges and
//! vertices as FreeCAD does: `Edge9` is the ninth distinct edge met by a depth-first walk, as
//! `TopExp::MapShapes` does) and the 3D curves of lines, circles and ellipses with their
//! placements. Every other section (2D curves, surfaces, polygons, triangulations) is parsed only
//! to be stepped over; a curve kind that is not kept is remembered by name, so that the caller can
//! say which kind it could not project.
//!
//! Layout of the format (facts from OpenCASCADE's `BRepTools_ShapeSet`, `TopTools_ShapeSet`,
//! `TopTools_LocationSet`, `GeomTools_*Set`): sections `Locations`, `Curve2ds`, `Curves`,
//! `Polygon3D`, `PolygonOnTriangulations`, `Surfaces`, `Triangulations`, `TShapes`, each with its
//! count; the shapes are written sub-shapes first, and a reference `+n l` means orientation `+`,
//! the shape `count − n + 1` (1-based), location `l` (0: identity); the last reference is the
//! shape itself.
//!
//! Everything read is bounded by the text: no count read from the file allocates more than the
//! tokens that remain, and walks of the topology are bounded in steps.

use std::fmt;

use super::geometry::parse_float_token;

/// Why a BRep text could not be read (a message for a `skipped` reason).
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) struct BrepError(pub(crate) String);

impl fmt::Display for BrepError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

type Res<T> = Result<T, BrepError>;

fn err<T>(msg: impl Into<String>) -> Res<T> {
    Err(BrepError(msg.into()))
}

/// A point or vector.
pub(crate) type V3 = [f64; 3];

/// An affine map `x ↦ M x + t` (OpenCASCADE's `gp_Trsf`, written as three rows of four).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Trsf {
    /// Rows `[m_i0, m_i1, m_i2, t_i]`.
    pub(crate) m: [[f64; 4]; 3],
}

impl Trsf {
    pub(crate) const IDENTITY: Trsf =
        Trsf { m: [[1.0, 0.0, 0.0, 0.0], [0.0, 1.0, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0]] };

    /// `self ∘ other` (apply `other` first).
    pub(crate) fn then_after(&self, other: &Trsf) -> Trsf {
        let a = &self.m;
        let b = &other.m;
        let mut m = [[0.0; 4]; 3];
        for (i, row) in m.iter_mut().enumerate() {
            for (j, cell) in row.iter_mut().enumerate() {
                let mut s = if j == 3 { a[i][3] } else { 0.0 };
                for (k, bk) in b.iter().enumerate() {
                    s += a[i][k] * bk[j];
                }
                *cell = s;
            }
        }
        Trsf { m }
    }

    pub(crate) fn point(&self, p: V3) -> V3 {
        let m = &self.m;
        [
            m[0][0] * p[0] + m[0][1] * p[1] + m[0][2] * p[2] + m[0][3],
            m[1][0] * p[0] + m[1][1] * p[1] + m[1][2] * p[2] + m[1][3],
            m[2][0] * p[0] + m[2][1] * p[1] + m[2][2] * p[2] + m[2][3],
        ]
    }

    pub(crate) fn vector(&self, v: V3) -> V3 {
        let m = &self.m;
        [
            m[0][0] * v[0] + m[0][1] * v[1] + m[0][2] * v[2],
            m[1][0] * v[0] + m[1][1] * v[1] + m[1][2] * v[2],
            m[2][0] * v[0] + m[2][1] * v[1] + m[2][2] * v[2],
        ]
    }

    fn det(&self) -> f64 {
        let m = &self.m;
        m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
            - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
            + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
    }

    /// The inverse map, `None` when it is singular.
    pub(crate) fn inverse(&self) -> Option<Trsf> {
        let d = self.det();
        if !d.is_finite() || d.abs() < 1e-300 {
            return None;
        }
        let m = &self.m;
        let c = |r0: usize, c0: usize, r1: usize, c1: usize| {
            m[r0][c0] * m[r1][c1] - m[r0][c1] * m[r1][c0]
        };
        let inv = [
            [c(1, 1, 2, 2) / d, -c(0, 1, 2, 2) / d, c(0, 1, 1, 2) / d],
            [-c(1, 0, 2, 2) / d, c(0, 0, 2, 2) / d, -c(0, 0, 1, 2) / d],
            [c(1, 0, 2, 1) / d, -c(0, 0, 2, 1) / d, c(0, 0, 1, 1) / d],
        ];
        let mut out = [[0.0; 4]; 3];
        for i in 0..3 {
            for j in 0..3 {
                out[i][j] = inv[i][j];
            }
            out[i][3] = -(inv[i][0] * m[0][3] + inv[i][1] * m[1][3] + inv[i][2] * m[2][3]);
        }
        Some(Trsf { m: out })
    }

    /// Whether the linear part is a rotation (orthonormal, determinant 1) within `tol`.
    pub(crate) fn is_rigid(&self, tol: f64) -> bool {
        let m = &self.m;
        for i in 0..3 {
            for j in 0..3 {
                let dot: f64 = (0..3).map(|k| m[k][i] * m[k][j]).sum();
                let want = if i == j { 1.0 } else { 0.0 };
                let ok = (dot - want).abs() <= tol;
                if !ok {
                    return false;
                }
            }
        }
        (self.det() - 1.0).abs() <= tol
    }
}

/// A location as OpenCASCADE keeps it: a product of powers of elementary transformations
/// (datums, by their index in the file), head first = the factor applied first. Two shapes are
/// the same sub-shape when their shapes and these chains are equal.
#[derive(Clone, Debug, PartialEq, Eq, Hash, Default)]
pub(crate) struct Chain(Vec<(usize, i32)>);

impl Chain {
    /// `outer * inner` as OpenCASCADE's `TopLoc_Location::Multiplied` forms it: the items of
    /// `inner` go in front, merging with equal datums at the junction.
    fn compose(outer: &Chain, inner: &Chain) -> Chain {
        // Worked tail first, so that the front is the end of the vector.
        let mut rev: Vec<(usize, i32)> = outer.0.iter().rev().copied().collect();
        for &(datum, power) in inner.0.iter().rev() {
            let mut p = power;
            if let Some(&(head, hp)) = rev.last()
                && head == datum
            {
                p = p.saturating_add(hp);
                rev.pop();
            }
            if p != 0 {
                rev.push((datum, p));
            }
        }
        rev.reverse();
        Chain(rev)
    }

    fn powered(&self, p: i32) -> Res<Chain> {
        if p.unsigned_abs() > 64 {
            return err(format!("location power {p} is out of range"));
        }
        let base = if p < 0 {
            // The inverse: reversed items with negated powers.
            Chain(self.0.iter().rev().map(|&(d, q)| (d, q.saturating_neg())).collect())
        } else {
            self.clone()
        };
        let mut out = Chain::default();
        for _ in 0..p.unsigned_abs() {
            out = Chain::compose(&out, &base);
            if out.0.len() > MAX_CHAIN {
                return err("location chain too long");
            }
        }
        Ok(out)
    }
}

/// A 3D curve kept for projection.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum Curve {
    /// `p + t d`.
    Line { p: V3, d: V3 },
    /// `p + r (cos t x + sin t y)`, normal `n`.
    Circle { p: V3, n: V3, x: V3, y: V3, r: f64 },
    /// `p + a cos t x + b sin t y`, normal `n`.
    Ellipse { p: V3, n: V3, x: V3, y: V3, a: f64, b: f64 },
    /// A kind that is not kept (its OpenCASCADE name: `B-spline`, `Bezier`, …).
    Other(&'static str),
}

impl Curve {
    /// The point at parameter `t`, `None` for a kind that is not kept.
    pub(crate) fn value(&self, t: f64) -> Option<V3> {
        let add = |p: V3, a: V3, s: f64| [p[0] + s * a[0], p[1] + s * a[1], p[2] + s * a[2]];
        match self {
            Curve::Line { p, d } => Some(add(*p, *d, t)),
            Curve::Circle { p, x, y, r, .. } => {
                Some(add(add(*p, *x, r * t.cos()), *y, r * t.sin()))
            }
            Curve::Ellipse { p, x, y, a, b, .. } => {
                Some(add(add(*p, *x, a * t.cos()), *y, b * t.sin()))
            }
            Curve::Other(_) => None,
        }
    }

    /// The curve mapped by `t` (directions re-normalised; the map must be rigid).
    pub(crate) fn transformed(&self, t: &Trsf) -> Curve {
        let unit = |v: V3| {
            let w = t.vector(v);
            let n = (w[0] * w[0] + w[1] * w[1] + w[2] * w[2]).sqrt();
            if n > 0.0 { [w[0] / n, w[1] / n, w[2] / n] } else { w }
        };
        match self {
            Curve::Line { p, d } => Curve::Line { p: t.point(*p), d: unit(*d) },
            Curve::Circle { p, n, x, y, r } => {
                Curve::Circle { p: t.point(*p), n: unit(*n), x: unit(*x), y: unit(*y), r: *r }
            }
            Curve::Ellipse { p, n, x, y, a, b } => Curve::Ellipse {
                p: t.point(*p),
                n: unit(*n),
                x: unit(*x),
                y: unit(*y),
                a: *a,
                b: *b,
            },
            Curve::Other(k) => Curve::Other(k),
        }
    }
}

/// The kind of a topological shape, in OpenCASCADE's order (`TopAbs_ShapeEnum`: the more complex
/// first).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub(crate) enum ShapeKind {
    Compound,
    CompSolid,
    Solid,
    Shell,
    Face,
    Wire,
    Edge,
    Vertex,
}

impl ShapeKind {
    fn from_token(t: &str) -> Option<ShapeKind> {
        Some(match t {
            "Co" => ShapeKind::Compound,
            "CS" => ShapeKind::CompSolid,
            "So" => ShapeKind::Solid,
            "Sh" => ShapeKind::Shell,
            "Fa" => ShapeKind::Face,
            "Wi" => ShapeKind::Wire,
            "Ed" => ShapeKind::Edge,
            "Ve" => ShapeKind::Vertex,
            _ => return None,
        })
    }
}

/// An edge's 3D curve: curve index (0-based), its location (a chain), parameter range.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct EdgeCurve {
    pub(crate) curve: Option<usize>,
    pub(crate) loc: usize,
    pub(crate) first: f64,
    pub(crate) last: f64,
}

#[derive(Clone, Debug)]
struct TShape {
    kind: ShapeKind,
    /// A vertex's point.
    point: Option<V3>,
    /// An edge's 3D curve, if it has one.
    edge: Option<EdgeCurve>,
    subs: Vec<SubRef>,
}

#[derive(Clone, Copy, Debug)]
struct SubRef {
    /// 0-based index into `shapes`.
    shape: usize,
    /// Location index (0: identity).
    loc: usize,
}

/// A sub-shape found by [`Brep::find`]: a vertex's point or an edge's curve, both in the shape's
/// coordinates (its location applied).
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum SubShape {
    Vertex(V3),
    /// The edge's 3D curve (placed) and its parameter range; `None` when the edge has no 3D
    /// curve.
    Edge(Option<(Curve, f64, f64)>),
    /// A face or another kind FreeCAD's external geometry does not take as an edge or vertex.
    Other(ShapeKind),
}

/// A parsed BRep.
#[derive(Debug)]
pub(crate) struct Brep {
    /// Location `i` (1-based) at index `i - 1`: its chain and transformation.
    locations: Vec<(Chain, Trsf)>,
    curves: Vec<Curve>,
    shapes: Vec<TShape>,
    root: SubRef,
}

/// The most steps of a topology walk.
const MAX_WALK: usize = 2_000_000;
/// The longest location chain.
const MAX_CHAIN: usize = 4096;

/// The text's whitespace-separated tokens, read lazily.
struct Tokens<'a> {
    text: &'a str,
    iter: std::iter::Peekable<std::str::SplitAsciiWhitespace<'a>>,
}

impl<'a> Tokens<'a> {
    fn new(text: &'a str) -> Tokens<'a> {
        Tokens { text, iter: text.split_ascii_whitespace().peekable() }
    }

    fn next(&mut self) -> Res<&'a str> {
        self.iter.next().map_or_else(|| err("unexpected end of the shape data"), Ok)
    }

    fn peek(&mut self) -> Option<&'a str> {
        self.iter.peek().copied()
    }

    /// An upper bound of the tokens left: half the bytes left, rounded up.
    fn remaining(&mut self) -> usize {
        let text_start = self.text.as_ptr() as usize;
        match self.iter.peek() {
            Some(t) => (self.text.len() - (t.as_ptr() as usize - text_start)).div_ceil(2),
            None => 0,
        }
    }

    fn real(&mut self) -> Res<f64> {
        let t = self.next()?;
        let x = parse_float_token(t).ok_or_else(|| BrepError(format!("'{t}' is not a number")))?;
        Ok(x)
    }

    fn int(&mut self) -> Res<i64> {
        let t = self.next()?;
        t.parse::<i64>().map_err(|_| BrepError(format!("'{t}' is not an integer")))
    }

    /// A count of items of at least `min_tokens` tokens each: refused when more than the tokens
    /// left could hold.
    fn count(&mut self, min_tokens: usize) -> Res<usize> {
        let n = self.int()?;
        let n = usize::try_from(n).map_err(|_| BrepError(format!("negative count {n}")))?;
        if n.saturating_mul(min_tokens.max(1)) > self.remaining() {
            return err(format!("count {n} exceeds the data"));
        }
        Ok(n)
    }

    fn index(&mut self, bound: usize, what: &str) -> Res<usize> {
        let i = self.int()?;
        match usize::try_from(i) {
            Ok(i) if i <= bound => Ok(i),
            _ => err(format!("{what} index {i} out of range (0..={bound})")),
        }
    }

    fn v3(&mut self) -> Res<V3> {
        Ok([self.real()?, self.real()?, self.real()?])
    }

    fn skip_reals(&mut self, n: usize) -> Res<()> {
        if n > self.remaining() {
            return err("unexpected end of the shape data");
        }
        for _ in 0..n {
            self.real()?;
        }
        Ok(())
    }

    fn expect(&mut self, word: &str) -> Res<()> {
        let t = self.next()?;
        if t == word { Ok(()) } else { err(format!("expected '{word}', found '{t}'")) }
    }
}

impl Brep {
    /// Parses a BRep text.
    pub(crate) fn parse(text: &str) -> Res<Brep> {
        let mut tk = Tokens::new(text);
        // The header (`CASCADE Topology V1, (c) Matra-Datavision`), up to `Locations`.
        let mut version = None;
        let mut header = 0;
        loop {
            let t =
                tk.next().map_err(|_| BrepError("no 'Locations' section: not a BRep".into()))?;
            if t == "Locations" {
                break;
            }
            header += 1;
            if header > 64 {
                return err("no 'Locations' section: not a BRep");
            }
            if version.is_none() {
                version =
                    t.strip_prefix('V').and_then(|v| v.trim_end_matches(',').parse::<u32>().ok());
            }
        }
        let version = version.unwrap_or(1);
        if version > 3 {
            return err(format!("BRep format version {version} is not supported"));
        }
        let locations = read_locations(&mut tk)?;
        let nloc = locations.len();
        tk.expect("Curve2ds")?;
        let n = tk.count(2)?;
        for _ in 0..n {
            skip_curve(&mut tk, 2, 0)?;
        }
        tk.expect("Curves")?;
        let n = tk.count(2)?;
        let mut curves = Vec::with_capacity(n.min(1 << 16));
        for _ in 0..n {
            curves.push(read_curve(&mut tk, 0)?);
        }
        tk.expect("Polygon3D")?;
        let n = tk.count(3)?;
        for _ in 0..n {
            let nodes = tk.count(3)?;
            let has_params = tk.int()?;
            tk.real()?; // deflection
            tk.skip_reals(3 * nodes)?;
            if has_params != 0 {
                tk.skip_reals(nodes)?;
            }
        }
        tk.expect("PolygonOnTriangulations")?;
        let n = tk.count(3)?;
        for _ in 0..n {
            let nodes = tk.count(1)?;
            tk.skip_reals(nodes)?;
            tk.expect("p")?;
            tk.real()?;
            let has_params = tk.int()?;
            if has_params != 0 {
                tk.skip_reals(nodes)?;
            }
        }
        tk.expect("Surfaces")?;
        let n = tk.count(2)?;
        for _ in 0..n {
            skip_surface(&mut tk, 0)?;
        }
        tk.expect("Triangulations")?;
        let n = tk.count(4)?;
        for _ in 0..n {
            let nodes = tk.count(3)?;
            let triangles = tk.count(3)?;
            let has_uv = tk.int()?;
            let has_normals = if version >= 3 { tk.int()? } else { 0 };
            tk.real()?;
            tk.skip_reals(3 * nodes)?;
            if has_uv != 0 {
                tk.skip_reals(2 * nodes)?;
            }
            tk.skip_reals(3 * triangles)?;
            if has_normals != 0 {
                tk.skip_reals(3 * nodes)?;
            }
        }
        tk.expect("TShapes")?;
        let n = tk.count(3)?;
        let mut shapes: Vec<TShape> = Vec::with_capacity(n.min(1 << 16));
        for i in 0..n {
            let kt = tk.next()?;
            let kind = ShapeKind::from_token(kt)
                .ok_or_else(|| BrepError(format!("unknown shape type '{kt}'")))?;
            let mut point = None;
            let mut edge = None;
            match kind {
                ShapeKind::Vertex => {
                    tk.real()?; // tolerance
                    point = Some(tk.v3()?);
                    loop {
                        tk.real()?; // parameter
                        let rep = tk.int()?;
                        match rep {
                            0 => break,
                            1 => {
                                tk.int()?; // curve
                            }
                            2 => {
                                tk.int()?; // pcurve
                                tk.int()?; // surface
                            }
                            3 => {
                                tk.real()?;
                                tk.int()?;
                            }
                            _ => return err(format!("unknown point representation {rep}")),
                        }
                        tk.index(nloc, "location")?;
                    }
                }
                ShapeKind::Edge => {
                    tk.real()?; // tolerance
                    tk.int()?; // same parameter
                    tk.int()?; // same range
                    tk.int()?; // degenerated
                    loop {
                        let rep = tk.int()?;
                        match rep {
                            0 => break,
                            1 => {
                                let c = tk.index(curves.len(), "curve")?;
                                let l = tk.index(nloc, "location")?;
                                let first = tk.real()?;
                                let last = tk.real()?;
                                if edge.is_none() {
                                    edge = Some(EdgeCurve {
                                        curve: c.checked_sub(1),
                                        loc: l,
                                        first,
                                        last,
                                    });
                                }
                            }
                            2 | 3 => {
                                tk.int()?; // pcurve
                                if rep == 3 {
                                    // The second pcurve, then the regularity (`C0`, `CN`, …),
                                    // which V1 writes glued to it (`121CN`).
                                    let t = tk.next()?;
                                    let digits = t.trim_start_matches(|c: char| c.is_ascii_digit());
                                    if digits.len() == t.len() {
                                        return err(format!("'{t}' is not a pcurve index"));
                                    }
                                    if digits.is_empty() {
                                        tk.next()?;
                                    }
                                }
                                tk.int()?; // surface
                                tk.index(nloc, "location")?;
                                tk.real()?;
                                tk.real()?;
                                if version >= 2 {
                                    tk.skip_reals(4)?; // UV points
                                }
                            }
                            4 => {
                                tk.next()?; // regularity
                                tk.int()?;
                                tk.index(nloc, "location")?;
                                tk.int()?;
                                tk.index(nloc, "location")?;
                            }
                            5 => {
                                tk.int()?;
                                tk.index(nloc, "location")?;
                            }
                            6 | 7 => {
                                tk.int()?;
                                if rep == 7 {
                                    tk.int()?;
                                }
                                tk.int()?;
                                tk.index(nloc, "location")?;
                            }
                            _ => return err(format!("unknown curve representation {rep}")),
                        }
                    }
                }
                ShapeKind::Face => {
                    tk.int()?; // natural restriction
                    tk.real()?; // tolerance
                    tk.int()?; // surface
                    tk.index(nloc, "location")?;
                    if tk.peek() == Some("2") {
                        tk.next()?;
                        tk.int()?; // triangulation
                    }
                }
                _ => {}
            }
            // The flags: a string of 0/1.
            let flags = tk.next()?;
            if flags.len() < 5 || !flags.bytes().all(|b| b == b'0' || b == b'1') {
                return err(format!("expected the shape flags, found '{flags}'"));
            }
            let mut subs = Vec::new();
            loop {
                let t = tk.next()?;
                if t == "*" {
                    break;
                }
                let r = read_ref(t, &mut tk, n, nloc)?;
                if r.shape >= i {
                    return err("a sub-shape refers forward");
                }
                subs.push(r);
            }
            shapes.push(TShape { kind, point, edge, subs });
        }
        if shapes.is_empty() {
            return err("the shape is empty");
        }
        let t = tk.next()?;
        let root = read_ref(t, &mut tk, n, nloc)?;
        Ok(Brep { locations, curves, shapes, root })
    }

    /// The `index`-th (1-based) distinct sub-shape of `kind` (edges or vertices) in the order of
    /// a depth-first walk, as FreeCAD's `Edge<n>` / `Vertex<n>` names count them.
    pub(crate) fn find(&self, kind: ShapeKind, index: usize) -> Res<SubShape> {
        if index == 0 {
            return err("sub-shape numbers start at 1");
        }
        let mut seen: std::collections::HashSet<(usize, Chain)> = std::collections::HashSet::new();
        let mut steps = 0usize;
        let root_chain = self.chain(self.root.loc);
        let mut stack: Vec<(usize, Chain)> = vec![(self.root.shape, root_chain)];
        while let Some((s, chain)) = stack.pop() {
            steps += 1;
            if steps > MAX_WALK {
                return err("the shape is too large to walk");
            }
            let shape = &self.shapes[s];
            if shape.kind == kind {
                if seen.insert((s, chain.clone())) && seen.len() == index {
                    return self.resolve(s, &chain);
                }
                continue;
            }
            if shape.kind > kind {
                continue;
            }
            steps += shape.subs.len();
            if steps > MAX_WALK {
                return err("the shape is too large to walk");
            }
            for sub in shape.subs.iter().rev() {
                let c = Chain::compose(&chain, &self.chain(sub.loc));
                if c.0.len() > MAX_CHAIN {
                    return err("location chain too long");
                }
                stack.push((sub.shape, c));
            }
        }
        err(format!("the shape has {} such sub-shapes", seen.len()))
    }

    fn chain(&self, loc: usize) -> Chain {
        if loc == 0 { Chain::default() } else { self.locations[loc - 1].0.clone() }
    }

    fn trsf_of(&self, chain: &Chain) -> Res<Trsf> {
        chain_trsf(&self.locations, chain)
    }

    fn resolve(&self, s: usize, chain: &Chain) -> Res<SubShape> {
        let shape = &self.shapes[s];
        let t = self.trsf_of(chain)?;
        match shape.kind {
            ShapeKind::Vertex => Ok(SubShape::Vertex(t.point(shape.point.unwrap_or([0.0; 3])))),
            ShapeKind::Edge => {
                let Some(ec) = &shape.edge else { return Ok(SubShape::Edge(None)) };
                let Some(ci) = ec.curve else { return Ok(SubShape::Edge(None)) };
                let Some(curve) = self.curves.get(ci) else { return err("bad curve index") };
                let t = t.then_after(&self.trsf_of(&self.chain(ec.loc))?);
                if !t.is_rigid(1e-9) {
                    return err("the edge's placement is not a rigid motion");
                }
                Ok(SubShape::Edge(Some((curve.transformed(&t), ec.first, ec.last))))
            }
            k => Ok(SubShape::Other(k)),
        }
    }
}

fn read_ref(t: &str, tk: &mut Tokens<'_>, n: usize, nloc: usize) -> Res<SubRef> {
    let mut chars = t.chars();
    let o = chars.next().unwrap_or(' ');
    if !matches!(o, '+' | '-' | 'i' | 'e') {
        return err(format!("expected a sub-shape reference, found '{t}'"));
    }
    let num: usize =
        chars.as_str().parse().map_err(|_| BrepError(format!("bad sub-shape reference '{t}'")))?;
    if num == 0 || num > n {
        return err(format!("sub-shape reference {num} out of range"));
    }
    let loc = tk.index(nloc, "location")?;
    Ok(SubRef { shape: n - num, loc })
}

/// The transformation of a chain: head first = applied first, `T = item_k ∘ … ∘ item_1`.
fn chain_trsf(locations: &[(Chain, Trsf)], chain: &Chain) -> Res<Trsf> {
    let total: u64 = chain.0.iter().map(|(_, p)| u64::from(p.unsigned_abs())).sum();
    if total > 100_000 {
        return err("location powers too large");
    }
    let mut t = Trsf::IDENTITY;
    for &(datum, p) in &chain.0 {
        let base = locations
            .get(datum.wrapping_sub(1))
            .map(|l| l.1)
            .ok_or_else(|| BrepError("bad location".into()))?;
        let f = if p < 0 {
            base.inverse().ok_or_else(|| BrepError("singular location".into()))?
        } else {
            base
        };
        for _ in 0..p.unsigned_abs() {
            t = f.then_after(&t);
        }
    }
    Ok(t)
}

fn read_locations(tk: &mut Tokens<'_>) -> Res<Vec<(Chain, Trsf)>> {
    let n = tk.count(2)?;
    let mut out: Vec<(Chain, Trsf)> = Vec::with_capacity(n.min(1 << 16));
    for i in 0..n {
        let kind = tk.int()?;
        match kind {
            1 => {
                let mut m = [[0.0; 4]; 3];
                for row in &mut m {
                    for cell in row.iter_mut() {
                        *cell = tk.real()?;
                    }
                }
                out.push((Chain(vec![(i + 1, 1)]), Trsf { m }));
            }
            2 => {
                let mut chain = Chain::default();
                loop {
                    let l = tk.index(i, "location")?;
                    if l == 0 {
                        break;
                    }
                    let p = tk.int()?;
                    let p = i32::try_from(p)
                        .map_err(|_| BrepError("location power out of range".into()))?;
                    let item = out[l - 1].0.powered(p)?;
                    // L = item * L (the item read last is the outermost factor).
                    chain = Chain::compose(&item, &chain);
                    if chain.0.len() > MAX_CHAIN {
                        return err("location chain too long");
                    }
                }
                let t = chain_trsf(&out, &chain)?;
                out.push((chain, t));
            }
            _ => return err(format!("unknown location type {kind}")),
        }
    }
    Ok(out)
}

/// Steps over a 2D (`dim` 2) or 3D (`dim` 3) curve record.
fn skip_curve(tk: &mut Tokens<'_>, dim: usize, depth: usize) -> Res<()> {
    if depth > 16 {
        return err("curves nested too deep");
    }
    let kind = tk.int()?;
    skip_curve_body(tk, kind, dim, depth)
}

/// Steps over the rest of a curve record of type `kind`.
fn skip_curve_body(tk: &mut Tokens<'_>, kind: i64, dim: usize, depth: usize) -> Res<()> {
    // Axis data: a location and 2 (2D: x, y axes) or 3 (3D: normal, x, y) directions.
    let axis = if dim == 2 { 2 + 2 + 2 } else { 3 + 9 };
    match kind {
        1 => tk.skip_reals(2 * dim),
        2 | 4 => tk.skip_reals(axis + 1),
        3 | 5 => tk.skip_reals(axis + 2),
        6 => {
            let rational = tk.int()?;
            let degree = tk.count(1)?;
            let per = dim + usize::from(rational != 0);
            let poles = degree + 1;
            tk.skip_reals(poles.saturating_mul(per))
        }
        7 => {
            let rational = tk.int()?;
            tk.int()?; // periodic
            tk.int()?; // degree
            let poles = tk.count(dim)?;
            let knots = tk.count(2)?;
            let per = dim + usize::from(rational != 0);
            tk.skip_reals(poles.saturating_mul(per))?;
            tk.skip_reals(2 * knots)
        }
        8 => {
            tk.skip_reals(2)?;
            skip_curve(tk, dim, depth + 1)
        }
        9 => {
            tk.skip_reals(if dim == 2 { 1 } else { 4 })?;
            skip_curve(tk, dim, depth + 1)
        }
        _ => err(format!("unknown curve type {kind}")),
    }
}

/// Reads a 3D curve record, keeping lines, circles and ellipses (and trimmed ones of them).
fn read_curve(tk: &mut Tokens<'_>, depth: usize) -> Res<Curve> {
    if depth > 16 {
        return err("curves nested too deep");
    }
    let kind = tk.int()?;
    match kind {
        1 => Ok(Curve::Line { p: tk.v3()?, d: tk.v3()? }),
        2 => {
            let (p, n, x, y) = (tk.v3()?, tk.v3()?, tk.v3()?, tk.v3()?);
            Ok(Curve::Circle { p, n, x, y, r: tk.real()? })
        }
        3 => {
            let (p, n, x, y) = (tk.v3()?, tk.v3()?, tk.v3()?, tk.v3()?);
            Ok(Curve::Ellipse { p, n, x, y, a: tk.real()?, b: tk.real()? })
        }
        8 => {
            tk.skip_reals(2)?;
            read_curve(tk, depth + 1)
        }
        _ => {
            skip_curve_body(tk, kind, 3, depth)?;
            Ok(Curve::Other(match kind {
                4 => "parabola",
                5 => "hyperbola",
                6 => "Bezier curve",
                7 => "B-spline curve",
                9 => "offset curve",
                _ => "curve",
            }))
        }
    }
}

/// Steps over a surface record.
fn skip_surface(tk: &mut Tokens<'_>, depth: usize) -> Res<()> {
    if depth > 16 {
        return err("surfaces nested too deep");
    }
    let kind = tk.int()?;
    match kind {
        1 => tk.skip_reals(12),
        2 | 4 => tk.skip_reals(13),
        3 | 5 => tk.skip_reals(14),
        6 => {
            tk.skip_reals(3)?;
            skip_curve(tk, 3, depth + 1)
        }
        7 => {
            tk.skip_reals(6)?;
            skip_curve(tk, 3, depth + 1)
        }
        8 => {
            let ur = tk.int()?;
            let vr = tk.int()?;
            let ud = tk.count(1)?;
            let vd = tk.count(1)?;
            let per = 3 + usize::from(ur != 0 || vr != 0);
            tk.skip_reals((ud + 1).saturating_mul(vd + 1).saturating_mul(per))
        }
        9 => {
            let ur = tk.int()?;
            let vr = tk.int()?;
            tk.int()?;
            tk.int()?;
            tk.int()?;
            tk.int()?;
            let nu = tk.count(1)?;
            let nv = tk.count(1)?;
            let nuk = tk.count(2)?;
            let nvk = tk.count(2)?;
            let per = 3 + usize::from(ur != 0 || vr != 0);
            tk.skip_reals(nu.saturating_mul(nv).saturating_mul(per))?;
            tk.skip_reals(2 * nuk)?;
            tk.skip_reals(2 * nvk)
        }
        10 => {
            tk.skip_reals(4)?;
            skip_surface(tk, depth + 1)
        }
        11 => {
            tk.skip_reals(1)?;
            skip_surface(tk, depth + 1)
        }
        _ => err(format!("unknown surface type {kind}")),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const SEGMENT: &str = "CASCADE Topology V1, (c) Matra-Datavision
Locations 1
1
1 0 0 0
0 1 0 0
0 0 1 1.5
Curve2ds 0
Curves 1
1 0 0 0 1 0 0
Polygon3D 0
PolygonOnTriangulations 0
Surfaces 0
Triangulations 0

TShapes 4
Ve
1e-07
0 0 0
0 0

0101101
*
Ve
1e-07
150 0 0
0 0

0101101
*
Ed
 1e-07 1 1 0
1  1 0 0 150
0

0101000
+4 0 -3 0 *
Wi

1101000
+2 0 *

+1 1
";

    #[test]
    fn segment_edges_and_vertices() {
        let b = Brep::parse(SEGMENT).unwrap();
        assert_eq!(b.find(ShapeKind::Vertex, 2).unwrap(), SubShape::Vertex([150.0, 0.0, 1.5]));
        match b.find(ShapeKind::Edge, 1).unwrap() {
            SubShape::Edge(Some((c, f, l))) => {
                assert_eq!(c.value(f), Some([0.0, 0.0, 1.5]));
                assert_eq!(c.value(l), Some([150.0, 0.0, 1.5]));
            }
            other => panic!("{other:?}"),
        }
        assert!(b.find(ShapeKind::Edge, 2).is_err());
    }

    #[test]
    fn chains_merge_like_toploc() {
        let a = Chain(vec![(3, -1)]);
        let b = Chain(vec![(3, 1), (5, 1)]);
        assert_eq!(Chain::compose(&b, &a), Chain(vec![(5, 1)]));
        assert_eq!(Chain(vec![(2, 1)]).powered(-1).unwrap(), Chain(vec![(2, -1)]));
    }

    #[test]
    fn garbage_is_an_error() {
        assert!(Brep::parse("").is_err());
        assert!(Brep::parse("Locations 99999999999").is_err());
        assert!(Brep::parse(&SEGMENT.replace("+4 0 -3 0", "+1 0 -3 0")).is_err());
    }
}
