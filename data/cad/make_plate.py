#!/usr/bin/env python3
"""Writes data/cad/plate.FCStd, a FreeCAD document written by hand for gcs (not saved by FreeCAD).

One Sketcher::SketchObject "Sketch" (label "Plate"): an 80 x 50 mm rectangle whose top-right corner
is rounded with a radius of 12.5 mm (an arc joined to the two sides by FreeCAD's end-point-to-end-point
Tangent constraints, as its fillet tool writes them), and a hole of diameter 15 mm at (25, 25).
Dimensions: DistanceX (width, and the hole's x from the sketch origin), DistanceY (height, and the
hole's y), Radius (the rounded corner), Diameter (the hole); the lower-left corner is on the origin.

The layout is FreeCAD 1.0's (geometry extensions, ExternalGeo holding the two axes). The document
has no FullyConstrained property: that flag records what FreeCAD's solver found, and FreeCAD never
solved this file. Only Document.xml is in the archive (no GuiDocument.xml, no thumbnail).

Usage: python3 data/cad/make_plate.py [OUTPUT]   (default: plate.FCStd beside this script)
Standard library only; deterministic (fixed time stamp: the same bytes with the same zlib).
"""

import math
import os
import sys
import zipfile

# Geometry, in FreeCAD's GeoId order (Edge1 is GeoId 0).
W, H, R = 80.0, 50.0, 12.5  # plate width, height, corner radius
HOLE = (25.0, 25.0, 7.5)  # hole centre and radius

# Lines: (start, end), the rectangle's sides in order, the top-right corner cut back by R.
LINES = [
    ((0.0, 0.0), (W, 0.0)),  # Edge1, bottom
    ((W, 0.0), (W, H - R)),  # Edge2, right
    ((W - R, H), (0.0, H)),  # Edge3, top
    ((0.0, H), (0.0, 0.0)),  # Edge4, left
]
# Edge5: the arc of the rounded corner, centre (W - R, H - R), counter-clockwise from angle 0
# (its start, on the right side) to pi/2 (its end, on the top side).
ARC = ((W - R, H - R), R, 0.0, math.pi / 2)
# Edge6: the hole.

GEO_UNDEF = -2000


def fmt(x):
    """A double as FreeCAD writes it: the shortest repr, integers without a decimal point."""
    if x == int(x) and abs(x) < 1e15:
        return str(int(x))
    return repr(x)


def extension(geo_id, construction=False):
    flags = "0" * 30 + ("10" if construction else "00")
    return (
        '                            <GeoExtensions count="1">\n'
        f'                                <GeoExtension type="Sketcher::SketchGeometryExtension" id="{geo_id}"'
        f' internalGeometryType="0" geometryModeFlags="{flags}" geometryLayer="0"/>\n'
        "                            </GeoExtensions>\n"
    )


def line_xml(geo_id, start, end, construction=False):
    return (
        f'                        <Geometry type="Part::GeomLineSegment" id="{geo_id}" migrated="1">\n'
        + extension(geo_id, construction)
        + f'                            <LineSegment StartX="{fmt(start[0])}" StartY="{fmt(start[1])}" StartZ="0"'
        f' EndX="{fmt(end[0])}" EndY="{fmt(end[1])}" EndZ="0"/>\n'
        "                        </Geometry>\n"
    )


def arc_xml(geo_id, centre, radius, a0, a1):
    return (
        f'                        <Geometry type="Part::GeomArcOfCircle" id="{geo_id}" migrated="1">\n'
        + extension(geo_id)
        + f'                            <ArcOfCircle CenterX="{fmt(centre[0])}" CenterY="{fmt(centre[1])}" CenterZ="0"'
        f' NormalX="0" NormalY="0" NormalZ="1" AngleXU="0" Radius="{fmt(radius)}"'
        f' StartAngle="{fmt(a0)}" EndAngle="{fmt(a1)}"/>\n'
        "                        </Geometry>\n"
    )


def circle_xml(geo_id, centre, radius):
    return (
        f'                        <Geometry type="Part::GeomCircle" id="{geo_id}" migrated="1">\n'
        + extension(geo_id)
        + f'                            <Circle CenterX="{fmt(centre[0])}" CenterY="{fmt(centre[1])}" CenterZ="0"'
        f' NormalX="0" NormalY="0" NormalZ="1" AngleXU="0" Radius="{fmt(radius)}"/>\n'
        "                        </Geometry>\n"
    )


# Constraints: (name, type code, value, (First, FirstPos), (Second, SecondPos)). Positions:
# 0 the curve, 1 start, 2 end, 3 centre; GeoId -1 at position 1 is the sketch's origin.
CONSTRAINTS = [
    ("", 1, 0, (0, 2), (1, 1)),  # Coincident: bottom's end, right's start
    ("", 1, 0, (2, 2), (3, 1)),  # Coincident: top's end, left's start
    ("", 1, 0, (3, 2), (0, 1)),  # Coincident: left's end, bottom's start
    ("", 2, 0, (0, 0), (GEO_UNDEF, 0)),  # Horizontal: bottom
    ("", 2, 0, (2, 0), (GEO_UNDEF, 0)),  # Horizontal: top
    ("", 3, 0, (1, 0), (GEO_UNDEF, 0)),  # Vertical: right
    ("", 3, 0, (3, 0), (GEO_UNDEF, 0)),  # Vertical: left
    ("", 5, 0, (1, 2), (4, 1)),  # Tangent, end point to end point: right's end, arc's start
    ("", 5, 0, (4, 2), (2, 1)),  # Tangent, end point to end point: arc's end, top's start
    ("", 1, 0, (0, 1), (-1, 1)),  # Coincident: bottom's start on the sketch origin
    ("width", 7, W, (0, 0), (GEO_UNDEF, 0)),  # DistanceX of the bottom side
    ("height", 8, H, (0, 1), (3, 1)),  # DistanceY from the bottom-left to the top-left corner
    ("corner", 11, R, (4, 0), (GEO_UNDEF, 0)),  # Radius of the rounded corner
    ("hole", 18, 2 * HOLE[2], (5, 0), (GEO_UNDEF, 0)),  # Diameter of the hole
    ("hole_x", 7, HOLE[0], (5, 3), (GEO_UNDEF, 0)),  # DistanceX of the hole's centre from the origin
    ("hole_y", 8, HOLE[1], (5, 3), (GEO_UNDEF, 0)),  # DistanceY of the hole's centre from the origin
]


def constraint_xml(name, code, value, first, second):
    return (
        f'                        <Constrain Name="{name}" Type="{code}" Value="{fmt(value)}"'
        f' First="{first[0]}" FirstPos="{first[1]}" Second="{second[0]}" SecondPos="{second[1]}"'
        f' Third="{GEO_UNDEF}" ThirdPos="0" LabelDistance="10" LabelPosition="0" IsDriving="1"'
        ' IsInVirtualSpace="0" IsActive="1" />\n'
    )


def document_xml():
    geometry = "".join(line_xml(i + 1, s, e) for i, (s, e) in enumerate(LINES))
    geometry += arc_xml(len(LINES) + 1, *ARC)
    geometry += circle_xml(len(LINES) + 2, HOLE[:2], HOLE[2])
    n_geo = len(LINES) + 2
    constraints = "".join(constraint_xml(*c) for c in CONSTRAINTS)
    axes = line_xml(-1, (0, 0), (1, 0), True) + line_xml(-2, (0, 0), (0, 1), True)
    return (
        "<?xml version='1.0' encoding='utf-8'?>\n"
        "<!--\n"
        " FreeCAD Document, see https://www.freecad.org for more information...\n"
        " Written by data/cad/make_plate.py for gcs, not saved by FreeCAD.\n"
        "-->\n"
        '<Document SchemaVersion="4" ProgramVersion="1.0.0R39109 (Git)" FileVersion="1">\n'
        '    <Properties Count="1" TransientCount="0">\n'
        '        <Property name="Label" type="App::PropertyString" status="1">\n'
        '            <String value="plate"/>\n'
        "        </Property>\n"
        "    </Properties>\n"
        '    <Objects Count="1" Dependencies="1">\n'
        '        <Object type="Sketcher::SketchObject" name="Sketch" id="1" Extensions="True" />\n'
        "    </Objects>\n"
        '    <ObjectData Count="1">\n'
        '        <Object name="Sketch" Extensions="True">\n'
        '            <Properties Count="6" TransientCount="0">\n'
        '                <Property name="Constraints" type="Sketcher::PropertyConstraintList">\n'
        f'                    <ConstraintList count="{len(CONSTRAINTS)}">\n'
        f"{constraints}"
        "                    </ConstraintList>\n"
        "                </Property>\n"
        '                <Property name="ExternalGeo" type="Part::PropertyGeometryList" status="16">\n'
        '                    <GeometryList count="2">\n'
        f"{axes}"
        "                    </GeometryList>\n"
        "                </Property>\n"
        '                <Property name="ExternalGeometry" type="App::PropertyLinkSubList">\n'
        '                    <LinkSubList count="0">\n'
        "                    </LinkSubList>\n"
        "                </Property>\n"
        '                <Property name="Geometry" type="Part::PropertyGeometryList" status="8192">\n'
        f'                    <GeometryList count="{n_geo}">\n'
        f"{geometry}"
        "                    </GeometryList>\n"
        "                </Property>\n"
        '                <Property name="Label" type="App::PropertyString" status="134217728">\n'
        '                    <String value="Plate"/>\n'
        "                </Property>\n"
        '                <Property name="Placement" type="App::PropertyPlacement">\n'
        '                    <PropertyPlacement Px="0" Py="0" Pz="0" Q0="0" Q1="0" Q2="0" Q3="1" A="0" Ox="0" Oy="0" Oz="1"/>\n'
        "                </Property>\n"
        "            </Properties>\n"
        "        </Object>\n"
        "    </ObjectData>\n"
        "</Document>\n"
    )


def check():
    """The drawing satisfies its constraints exactly as written (arc ends as a reader computes them)."""
    (cx, cy), r, a0, a1 = ARC
    start = (cx + r * math.cos(a0), cy + r * math.sin(a0))
    end = (cx + r * math.cos(a1), cy + r * math.sin(a1))
    assert start == LINES[1][1], start  # the arc starts where the right side ends
    assert end == LINES[2][0], end  # and ends where the top starts
    assert LINES[0][1] == LINES[1][0] and LINES[2][1] == LINES[3][0] and LINES[3][1] == LINES[0][0]


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "plate.FCStd")
    check()
    info = zipfile.ZipInfo("Document.xml", date_time=(2025, 1, 1, 0, 0, 0))
    info.compress_type = zipfile.ZIP_DEFLATED
    info.external_attr = 0o644 << 16
    with zipfile.ZipFile(out, "w") as z:
        z.writestr(info, document_xml())
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
