//! SolveSpace's numeric type codes (`src/sketch.h`) and their names, for the mapping and for
//! messages.

/// `Group::Type`.
pub(super) mod group {
    pub(in crate::slvs) const DRAWING_3D: i64 = 5000;
    pub(in crate::slvs) const DRAWING_WORKPLANE: i64 = 5001;

    /// The name of a group type.
    pub(in crate::slvs) fn name(ty: i64) -> &'static str {
        match ty {
            5000 => "DRAWING_3D",
            5001 => "DRAWING_WORKPLANE",
            5100 => "EXTRUDE",
            5101 => "LATHE",
            5102 => "REVOLVE",
            5103 => "HELIX",
            5200 => "ROTATE",
            5201 => "TRANSLATE",
            5300 => "LINKED",
            _ => "unknown group type",
        }
    }
}

/// `Request::Type`.
pub(super) mod request {
    pub(in crate::slvs) const WORKPLANE: i64 = 100;
    pub(in crate::slvs) const DATUM_POINT: i64 = 101;
}

/// `Entity::Type`.
pub(super) mod entity {
    pub(in crate::slvs) const POINT_IN_3D: i64 = 2000;
    pub(in crate::slvs) const POINT_IN_2D: i64 = 2001;
    pub(in crate::slvs) const DISTANCE: i64 = 4000;
    pub(in crate::slvs) const WORKPLANE: i64 = 10000;
    pub(in crate::slvs) const LINE_SEGMENT: i64 = 11000;
    pub(in crate::slvs) const CUBIC: i64 = 12000;
    pub(in crate::slvs) const CUBIC_PERIODIC: i64 = 12001;
    pub(in crate::slvs) const CIRCLE: i64 = 13000;
    pub(in crate::slvs) const ARC_OF_CIRCLE: i64 = 14000;

    /// Any of the point types (`POINT_IN_3D` … `POINT_N_ROT_AXIS_TRANS`).
    pub(in crate::slvs) fn is_point(ty: i64) -> bool {
        (2000..=2014).contains(&ty)
    }

    /// Any of the normal types.
    pub(in crate::slvs) fn is_normal(ty: i64) -> bool {
        (3000..=3012).contains(&ty)
    }

    /// Any of the face types.
    pub(in crate::slvs) fn is_face(ty: i64) -> bool {
        (5000..=5006).contains(&ty)
    }

    /// The name of an entity type.
    pub(in crate::slvs) fn name(ty: i64) -> &'static str {
        match ty {
            2000 => "POINT_IN_3D",
            2001 => "POINT_IN_2D",
            2010 => "POINT_N_TRANS",
            2011 => "POINT_N_ROT_TRANS",
            2012 => "POINT_N_COPY",
            2013 => "POINT_N_ROT_AA",
            2014 => "POINT_N_ROT_AXIS_TRANS",
            3000 => "NORMAL_IN_3D",
            3001 => "NORMAL_IN_2D",
            3010 => "NORMAL_N_COPY",
            3011 => "NORMAL_N_ROT",
            3012 => "NORMAL_N_ROT_AA",
            4000 => "DISTANCE",
            4001 => "DISTANCE_N_COPY",
            5000 => "FACE_NORMAL_PT",
            5001 => "FACE_XPROD",
            5002 => "FACE_N_ROT_TRANS",
            5003 => "FACE_N_TRANS",
            5004 => "FACE_N_ROT_AA",
            5005 => "FACE_ROT_NORMAL_PT",
            5006 => "FACE_N_ROT_AXIS_TRANS",
            10000 => "WORKPLANE",
            11000 => "LINE_SEGMENT",
            12000 => "CUBIC",
            12001 => "CUBIC_PERIODIC",
            13000 => "CIRCLE",
            14000 => "ARC_OF_CIRCLE",
            15000 => "TTF_TEXT",
            16000 => "IMAGE",
            _ => "unknown entity type",
        }
    }
}

/// `Constraint::Type`.
pub(super) mod constraint {
    pub(in crate::slvs) const POINTS_COINCIDENT: i64 = 20;
    pub(in crate::slvs) const PT_PT_DISTANCE: i64 = 30;
    pub(in crate::slvs) const PT_PLANE_DISTANCE: i64 = 31;
    pub(in crate::slvs) const PT_LINE_DISTANCE: i64 = 32;
    pub(in crate::slvs) const PT_FACE_DISTANCE: i64 = 33;
    pub(in crate::slvs) const PROJ_PT_DISTANCE: i64 = 34;
    pub(in crate::slvs) const PT_IN_PLANE: i64 = 41;
    pub(in crate::slvs) const PT_ON_LINE: i64 = 42;
    pub(in crate::slvs) const PT_ON_FACE: i64 = 43;
    pub(in crate::slvs) const EQUAL_LENGTH_LINES: i64 = 50;
    pub(in crate::slvs) const LENGTH_RATIO: i64 = 51;
    pub(in crate::slvs) const EQ_LEN_PT_LINE_D: i64 = 52;
    pub(in crate::slvs) const EQ_PT_LN_DISTANCES: i64 = 53;
    pub(in crate::slvs) const EQUAL_ANGLE: i64 = 54;
    pub(in crate::slvs) const EQUAL_LINE_ARC_LEN: i64 = 55;
    pub(in crate::slvs) const LENGTH_DIFFERENCE: i64 = 56;
    pub(in crate::slvs) const SYMMETRIC: i64 = 60;
    pub(in crate::slvs) const SYMMETRIC_HORIZ: i64 = 61;
    pub(in crate::slvs) const SYMMETRIC_VERT: i64 = 62;
    pub(in crate::slvs) const SYMMETRIC_LINE: i64 = 63;
    pub(in crate::slvs) const AT_MIDPOINT: i64 = 70;
    pub(in crate::slvs) const HORIZONTAL: i64 = 80;
    pub(in crate::slvs) const VERTICAL: i64 = 81;
    pub(in crate::slvs) const DIAMETER: i64 = 90;
    pub(in crate::slvs) const PT_ON_CIRCLE: i64 = 100;
    pub(in crate::slvs) const SAME_ORIENTATION: i64 = 110;
    pub(in crate::slvs) const ANGLE: i64 = 120;
    pub(in crate::slvs) const PARALLEL: i64 = 121;
    pub(in crate::slvs) const PERPENDICULAR: i64 = 122;
    pub(in crate::slvs) const ARC_LINE_TANGENT: i64 = 123;
    pub(in crate::slvs) const CUBIC_LINE_TANGENT: i64 = 124;
    pub(in crate::slvs) const CURVE_CURVE_TANGENT: i64 = 125;
    pub(in crate::slvs) const EQUAL_RADIUS: i64 = 130;
    pub(in crate::slvs) const WHERE_DRAGGED: i64 = 200;
    pub(in crate::slvs) const ARC_ARC_LEN_RATIO: i64 = 210;
    pub(in crate::slvs) const ARC_LINE_LEN_RATIO: i64 = 211;
    pub(in crate::slvs) const ARC_ARC_DIFFERENCE: i64 = 212;
    pub(in crate::slvs) const ARC_LINE_DIFFERENCE: i64 = 213;
    pub(in crate::slvs) const COMMENT: i64 = 1000;

    /// The name of a constraint type.
    pub(in crate::slvs) fn name(ty: i64) -> &'static str {
        match ty {
            20 => "POINTS_COINCIDENT",
            30 => "PT_PT_DISTANCE",
            31 => "PT_PLANE_DISTANCE",
            32 => "PT_LINE_DISTANCE",
            33 => "PT_FACE_DISTANCE",
            34 => "PROJ_PT_DISTANCE",
            41 => "PT_IN_PLANE",
            42 => "PT_ON_LINE",
            43 => "PT_ON_FACE",
            50 => "EQUAL_LENGTH_LINES",
            51 => "LENGTH_RATIO",
            52 => "EQ_LEN_PT_LINE_D",
            53 => "EQ_PT_LN_DISTANCES",
            54 => "EQUAL_ANGLE",
            55 => "EQUAL_LINE_ARC_LEN",
            56 => "LENGTH_DIFFERENCE",
            60 => "SYMMETRIC",
            61 => "SYMMETRIC_HORIZ",
            62 => "SYMMETRIC_VERT",
            63 => "SYMMETRIC_LINE",
            70 => "AT_MIDPOINT",
            80 => "HORIZONTAL",
            81 => "VERTICAL",
            90 => "DIAMETER",
            100 => "PT_ON_CIRCLE",
            110 => "SAME_ORIENTATION",
            120 => "ANGLE",
            121 => "PARALLEL",
            122 => "PERPENDICULAR",
            123 => "ARC_LINE_TANGENT",
            124 => "CUBIC_LINE_TANGENT",
            125 => "CURVE_CURVE_TANGENT",
            130 => "EQUAL_RADIUS",
            200 => "WHERE_DRAGGED",
            210 => "ARC_ARC_LEN_RATIO",
            211 => "ARC_LINE_LEN_RATIO",
            212 => "ARC_ARC_DIFFERENCE",
            213 => "ARC_LINE_DIFFERENCE",
            1000 => "COMMENT",
            _ => "unknown constraint type",
        }
    }

    /// Whether the constraint has a dimension (SolveSpace's `HasLabel`, without the comment):
    /// what `Group.allDimsReference` turns into reference dimensions.
    pub(in crate::slvs) fn is_dimension(ty: i64) -> bool {
        matches!(ty, 30..=34 | 90 | 51 | 56 | 120 | 210..=213)
    }

    /// Whether SolveSpace projects the constraint into its workplane (`IsProjectible`, plus the
    /// tangencies and the symmetries that use the workplane's normal or axes).
    pub(in crate::slvs) fn uses_workplane(ty: i64) -> bool {
        !matches!(ty, 31 | 33 | 34 | 41 | 43 | 55 | 90 | 100 | 110 | 123 | 130)
    }
}
