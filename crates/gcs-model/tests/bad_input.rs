//! Every error the format lists (docs/format.md §1, "Errors") has a small bad file in
//! `tests/bad/`; each must give exactly one clear message naming the file, the position and the
//! offending id or field.

use std::path::Path;

use gcs_model::System;

fn message(file: &str) -> String {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/bad").join(file);
    let text = std::fs::read_to_string(&path).unwrap();
    match System::from_ron_str(&text, Some(file)) {
        Ok(s) => panic!("{file} was accepted: {s}"),
        Err(e) => e.to_string(),
    }
}

#[test]
fn every_bad_file_has_its_message() {
    let expected = [
        ("syntax.ron", "syntax.ron:4:5: RON syntax: Expected comma"),
        (
            "unknown_id.ron",
            "unknown_id.ron:4:48: constraint \"d\": field b: unknown entity id \"r\"",
        ),
        (
            "duplicate_id.ron",
            "duplicate_id.ron:4:34: duplicate id \"q\" (ids must be unique across entities and constraints)",
        ),
        (
            "kind_mismatch.ron",
            "kind_mismatch.ron:4:19: constraint \"t\": Tangent does not apply to point–line in 2D (it takes line–circle or circle–circle)",
        ),
        (
            "wrong_constraint_dim.ron",
            "wrong_constraint_dim.ron:4:19: constraint \"i\": Incident does not apply to line–circle in 2D (it takes point–line or point–circle)",
        ),
        (
            "horizontal_in_3d.ron",
            "horizontal_in_3d.ron:4:19: constraint \"h\": Horizontal does not apply to segment in 3D (it takes a line or segment, in 2D only)",
        ),
        (
            "wrong_dimension.ron",
            "wrong_dimension.ron:3:35: entity \"p\": field at: expected 2 coordinates in 2D, found 3",
        ),
        (
            "line_position_count.ron",
            "line_position_count.ron:3:34: entity \"l\": field at: expected 2 positions, found 1",
        ),
        (
            "segment_coincident.ron",
            "segment_coincident.ron:6:9: entity \"s\": its points \"p\" and \"q\" coincide in the sketch",
        ),
        (
            "segment_self.ron",
            "segment_self.ron:3:76: entity \"s\": field to: segment from \"p\" to itself",
        ),
        (
            "segment_endpoint.ron",
            "segment_endpoint.ron:3:113: entity \"s\": field to: a segment joins two points, \"l\" is a line",
        ),
        (
            "line_degenerate.ron",
            "line_degenerate.ron:3:34: entity \"l\": field at: the two points of the line coincide",
        ),
        (
            "plane_zero_normal.ron",
            "plane_zero_normal.ron:3:36: entity \"pl\": field at: the normal of the plane is zero",
        ),
        (
            "negative_distance.ron",
            "negative_distance.ron:4:60: constraint \"d\": field value: must not be negative, found -1.5",
        ),
        (
            "negative_radius.ron",
            "negative_radius.ron:3:56: entity \"c\": field radius: must not be negative, found -2",
        ),
        (
            "nonfinite_distance.ron",
            "nonfinite_distance.ron:4:60: constraint \"d\": field value: not a finite number",
        ),
        (
            "not_a_number.ron",
            "not_a_number.ron:3:35: entity \"p\": field at: \"one\" is not a number (write an integer, a decimal or \"p/q\")",
        ),
        (
            "fix_without_position.ron",
            "fix_without_position.ron:4:19: constraint \"f\": Fix on \"p\", which has no sketch position to pin it at",
        ),
        (
            "unsupported_dim.ron",
            "unsupported_dim.ron:3:10: field dim: unsupported dimension 4 (expected 2 or 3)",
        ),
        (
            "circle_in_3d.ron",
            "circle_in_3d.ron:3:16: entity \"c\": a circle does not exist in 3D (circles are 2D, planes and spheres 3D)",
        ),
        (
            "unknown_field.ron",
            "unknown_field.ron:3:31: RON syntax: Unexpected field named `att` in `Point`, expected one of `id`, `at`, or `construction` instead",
        ),
        (
            "unknown_variant.ron",
            "unknown_variant.ron:3:16: RON syntax: Unexpected variant named `Pt` in enum `Entity`, expected one of `Point`, `Line`, `Segment`, `Circle`, `Plane`, `Sphere`, `Arc`, or `BSpline` instead",
        ),
        (
            "constraint_unknown_field.ron",
            "constraint_unknown_field.ron:3:51: RON syntax: Unexpected field named `valu` in `Distance`, expected one of `id`, `a`, `b`, or `value` instead",
        ),
        (
            "constraint_unknown_variant.ron",
            "constraint_unknown_variant.ron:3:17: RON syntax: Unexpected variant named `Distanc` in enum `Constraint`, expected one of `Coincident`, `Distance`, `Angle`, `Parallel`, `Perpendicular`, `Incident`, `Tangent`, `Concentric`, `Radius`, `EqualLength`, `Midpoint`, `Symmetric`, `Horizontal`, `Vertical`, `Fix`, `EqualRadius`, `DistanceX`, `DistanceY`, `TangentAt`, `LengthRatio`, `EqualAngle`, `EqualDistance`, `SplinePoint`, or `Orientation` instead",
        ),
        (
            "constraint_missing_field.ron",
            "constraint_missing_field.ron:3:41: RON syntax: Unexpected missing field named `b` in `Distance`",
        ),
        (
            "constraint_value_not_taken.ron",
            "constraint_value_not_taken.ron:3:53: RON syntax: Unexpected field named `value` in `Coincident`, expected one of `id`, `a`, or `b` instead",
        ),
        (
            "constraint_as_entity.ron",
            "constraint_as_entity.ron:6:38: constraint \"d\": field b: \"h\" is a constraint, not an entity",
        ),
        (
            "orientation_count.ron",
            "orientation_count.ron:4:48: constraint \"o\": Orientation: field points: 3 points in 2D, found 2",
        ),
        (
            "orientation_sign.ron",
            "orientation_sign.ron:4:71: constraint \"o\": Orientation: field sign: sign 2: 1 or -1",
        ),
        (
            "orientation_not_point.ron",
            "orientation_not_point.ron:4:48: constraint \"o\": Orientation: field points: \"l\" is a line, not a point",
        ),
        (
            "group_repeated.ron",
            "group_repeated.ron:5:39: group \"g\": field entities: \"p\" is named twice",
        ),
        (
            "bspline_pole_not_point.ron",
            "bspline_pole_not_point.ron:4:40: entity \"s\": field poles: a B-spline's control points are points, \"c\" is a circle",
        ),
        (
            "bspline_knots.ron",
            "bspline_knots.ron:5:20: entity \"s\": field knots: 5 knots where 6 are expected (control points + degree + 1)",
        ),
        (
            "reference_not_dimension.ron",
            "reference_not_dimension.ron:5:45: constraint \"h\": field reference: a reference (driven) Horizontal is not a dimension: only dimensions (Distance, Angle, Radius, DistanceX, DistanceY, LengthRatio) are measured",
        ),
        (
            "repeated_entity.ron",
            "repeated_entity.ron:4:48: constraint \"d\": fields a and b both name \"p\"",
        ),
    ];
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/bad");
    let mut on_disk: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    on_disk.sort();
    let mut listed: Vec<String> = expected.iter().map(|(f, _)| f.to_string()).collect();
    listed.sort();
    assert_eq!(on_disk, listed, "every bad file has an expectation and vice versa");
    for (file, want) in expected {
        assert_eq!(message(file), want, "{file}");
    }
}

#[test]
fn errors_without_origin_still_have_positions() {
    let e = System::from_ron_str("System(dim: 2, entities: [Point(id: \"p\", at: [1])])", None)
        .unwrap_err();
    assert_eq!(
        e.to_string(),
        "1:46: entity \"p\": field at: expected 2 coordinates in 2D, found 1"
    );
    assert!(e.position.is_some());
}
