#!/usr/bin/env python3
"""Generates examples/example_building.gml, the small IndoorGML 1.0.3 building shipped with conicloc.

Usage: scripts/make_example_building.py [OUT.gml]   (default: examples/example_building.gml)

Python 3 standard library only; the output is deterministic (same bytes on every run), so the
generated file is committed and a re-run shows no diff.

The building (map frame: metres, x east, y north, z up; no CRS, local coordinates):
  - footprint about 18 m x 10 m, two storeys: floor 0 at z = 0 (clear height 3.0 m), a 0.2 m
    slab, floor 1 at z = 3.2 (clear height 3.0 m);
  - south band (y 0..4): floor 0 rooms A (x 0..6) and B (x 6..12), floor 1 an open-plan office
    (x 0..12); on both floors room C east of them, bounded by the slanted east facade
    x = 18 - y tan 30 deg (a non-Manhattan wall, 30 deg to the y axis);
  - a 2 m wide corridor (y 4..6) on both floors, from the west facade to the slanted facade;
  - north band (y 6..10): room D (x 6.5..facade); on floor 1 its ceiling slopes from 3.0 m at the
    corridor down to 2.2 m at the north facade (a sloped roof, 11 deg);
  - a staircase (x 0..6.5, y 6..8), one TransitionSpace spanning both storeys: bottom landing at
    z = 0, a 37 deg flight, top landing at z = 3.2;
  - doors 0.9 m x 2.1 m between rooms and corridor, between rooms A and B, and from the corridor
    to both stair landings; an entrance in the west facade; windows in exterior walls, one of them
    in the slanted facade.

Encoding choices (real files vary; these are the ones made here):
  - thin walls: adjacent cells share wall planes, so every inner wall appears twice (once per
    cell), as in most real models;
  - every cell is a gml:Solid whose shell polygons are oriented OUTWARD (counter-clockwise seen
    from outside the cell, normal pointing away from the cell interior);
  - a door is a notch in the outer ring of each wall polygon it pierces (a door reaches the floor,
    and a GML interior ring must not touch the exterior ring); a window is a gml:interior ring;
  - every door is a navi:ConnectionBoundary polygon whose normal points from the first to the
    second cell it joins, dual to one core:Transition between the two cells' States; the entrance
    is a navi:AnchorBoundary (indoor to outdoor, no Transition); windows are core:CellSpaceBoundary;
  - rings are closed (first position repeated), positions in gml:posList srsDimension="3".
"""

import math
import os
import sys
import xml.etree.ElementTree as ET

TAN30 = math.tan(math.radians(30.0))
SLAB_M = 0.2
CLEAR_HEIGHT_M = 3.0
STOREY_Z = [0.0, CLEAR_HEIGHT_M + SLAB_M]  # floor level of each storey
DOOR_WIDTH_M = 0.9
DOOR_HEIGHT_M = 2.1
STATE_HEIGHT_M = 0.5  # navigation points float this far above the floor, as in real files


def facade_x(y):
    """x of the slanted east facade at northing y."""
    return 18.0 - y * TAN30


def fmt(value):
    """Fixed 6 decimals with trailing zeros removed: deterministic and compact."""
    text = f"{value:.6f}".rstrip("0").rstrip(".")
    return "0" if text in ("-0", "") else text


def pos_text(points):
    return " ".join(" ".join(fmt(c) for c in p) for p in points)


class Cell:
    """A prism cell: footprint (counter-clockwise from above), floor and ceiling height functions.

    `floor_profile` optionally replaces the flat floor by a profile along x (the stair)."""

    def __init__(self, ident, name, cls, storey, footprint, floor_z, ceiling_z, description,
                 floor_profile=None):
        self.id = ident
        self.name = name
        self.cls = cls  # (namespace prefix, local name)
        self.storey = storey
        self.footprint = footprint
        self.floor_z = floor_z  # f(x, y) -> z
        self.ceiling_z = ceiling_z  # g(x, y) -> z
        self.description = description
        self.floor_profile = floor_profile  # [(x, z), ...] increasing x; None for a flat floor
        self.boundaries = []  # gml:ids of the boundaries it is partially bounded by

    def centroid_xy(self):
        area = cx = cy = 0.0
        n = len(self.footprint)
        for i in range(n):
            (x0, y0), (x1, y1) = self.footprint[i], self.footprint[(i + 1) % n]
            cross = x0 * y1 - x1 * y0
            area += cross
            cx += (x0 + x1) * cross
            cy += (y0 + y1) * cross
        return cx / (3.0 * area), cy / (3.0 * area)

    def state_point(self):
        x, y = self.centroid_xy()
        return (x, y, self.floor_z(x, y) + STATE_HEIGHT_M)


class Opening:
    """A door or window: a vertical rectangle from (x0, y0) to (x1, y1), z0..z1."""

    def __init__(self, ident, kind, p0, p1, z0, z1, cells, name):
        self.id = ident
        self.kind = kind  # "door", "entrance" or "window"
        self.p0, self.p1 = p0, p1
        self.z0, self.z1 = z0, z1
        self.cells = cells  # ids of the cells it joins (1 or 2)
        self.name = name

    def center(self):
        return ((self.p0[0] + self.p1[0]) / 2, (self.p0[1] + self.p1[1]) / 2,
                (self.z0 + self.z1) / 2)


def flat(z):
    return lambda x, y: z


def building():
    cells = []
    openings = []
    for storey, z in enumerate(STOREY_Z):
        top = z + CLEAR_HEIGHT_M
        tag = f"F{storey}"
        if storey == 0:
            cells.append(Cell(f"{tag}-RoomA", "Room A", ("navi", "GeneralSpace"), storey,
                              [(0, 0), (6, 0), (6, 4), (0, 4)], flat(z), flat(top),
                              "office, floor 0"))
            cells.append(Cell(f"{tag}-RoomB", "Room B", ("navi", "GeneralSpace"), storey,
                              [(6, 0), (12, 0), (12, 4), (6, 4)], flat(z), flat(top),
                              "office, floor 0"))
        else:
            cells.append(Cell(f"{tag}-Office", "Open-plan office", ("navi", "GeneralSpace"),
                              storey, [(0, 0), (12, 0), (12, 4), (0, 4)], flat(z), flat(top),
                              "open-plan office, floor 1"))
        cells.append(Cell(f"{tag}-RoomC", "Room C", ("navi", "GeneralSpace"), storey,
                          [(12, 0), (facade_x(0), 0), (facade_x(4), 4), (12, 4)], flat(z),
                          flat(top), f"room at the slanted east facade, floor {storey}"))
        cells.append(Cell(f"{tag}-Corridor", "Corridor", ("navi", "TransitionSpace"), storey,
                          [(0, 4), (facade_x(4), 4), (facade_x(6), 6), (0, 6)], flat(z),
                          flat(top), f"corridor, floor {storey}"))
        if storey == 0:
            ceiling_d = flat(top)
            description = "north room, floor 0"
        else:
            # Mono-pitch roof: 3.0 m at the corridor wall (y = 6), 2.2 m at the facade (y = 10).
            ceiling_d = lambda x, y, z=z: z + CLEAR_HEIGHT_M - 0.8 * (y - 6.0) / 4.0
            description = "north room under a sloped roof, floor 1"
        cells.append(Cell(f"{tag}-RoomD", "Room D", ("navi", "GeneralSpace"), storey,
                          [(6.5, 6), (facade_x(6), 6), (facade_x(10), 10), (6.5, 10)], flat(z),
                          ceiling_d, description))

    # The staircase: landings x 0..1.2 (z 0) and 5.4..6.5 (z 3.2), flight between them.
    upper = STOREY_Z[1]
    profile = [(0.0, 0.0), (1.2, 0.0), (5.4, upper), (6.5, upper)]

    def stair_floor(x, y):
        for (xa, za), (xb, zb) in zip(profile, profile[1:]):
            if x <= xb:
                return za + (zb - za) * (x - xa) / (xb - xa)
        return profile[-1][1]

    cells.append(Cell("Stair", "Staircase", ("navi", "TransitionSpace"), 0,
                      [(0, 6), (6.5, 6), (6.5, 8), (0, 8)], stair_floor,
                      flat(upper + CLEAR_HEIGHT_M), "staircase from floor 0 to floor 1",
                      floor_profile=profile))

    def door(ident, name, a, b, p0, p1, z):
        openings.append(Opening(ident, "door", p0, p1, z, z + DOOR_HEIGHT_M, [a, b], name))

    def window(ident, name, cell, p0, p1, z0, z1):
        openings.append(Opening(ident, "window", p0, p1, z0, z1, [cell], name))

    z0, z1 = STOREY_Z
    door("F0-Door-A", "door room A - corridor", "F0-RoomA", "F0-Corridor", (2.5, 4), (3.4, 4), z0)
    door("F0-Door-B", "door room B - corridor", "F0-RoomB", "F0-Corridor", (8.5, 4), (9.4, 4), z0)
    door("F0-Door-AB", "door room A - room B", "F0-RoomA", "F0-RoomB", (6, 1.5), (6, 2.4), z0)
    door("F0-Door-C", "door room C - corridor", "F0-RoomC", "F0-Corridor", (13.0, 4), (13.9, 4),
         z0)
    door("F0-Door-D", "door room D - corridor", "F0-RoomD", "F0-Corridor", (10.0, 6), (10.9, 6),
         z0)
    door("F0-Door-Stair", "door corridor - stair (bottom landing)", "F0-Corridor", "Stair",
         (0.2, 6), (1.1, 6), z0)
    door("F1-Door-Office", "door office - corridor", "F1-Office", "F1-Corridor", (9.0, 4),
         (9.9, 4), z1)
    door("F1-Door-C", "door room C - corridor", "F1-RoomC", "F1-Corridor", (13.0, 4), (13.9, 4),
         z1)
    door("F1-Door-D", "door room D - corridor", "F1-RoomD", "F1-Corridor", (10.0, 6), (10.9, 6),
         z1)
    door("F1-Door-Stair", "door corridor - stair (top landing)", "F1-Corridor", "Stair",
         (5.5, 6), (6.4, 6), z1)
    openings.append(Opening("F0-Entrance", "entrance", (0, 5.45), (0, 4.55), z0,
                            z0 + DOOR_HEIGHT_M, ["F0-Corridor"], "main entrance (west facade)"))

    window("F0-Window-A", "window room A (south)", "F0-RoomA", (2.0, 0), (4.0, 0), 0.9, 2.1)
    window("F0-Window-B", "window room B (south)", "F0-RoomB", (8.0, 0), (10.0, 0), 0.9, 2.1)
    s0, s1 = 1.0, 3.0  # along the slanted facade, measured as northing
    window("F0-Window-C", "window room C (slanted east facade)", "F0-RoomC",
           (facade_x(s0), s0), (facade_x(s1), s1), 0.9, 2.1)
    window("F1-Window-Office-1", "window office (south, west)", "F1-Office", (2.0, 0), (4.0, 0),
           z1 + 0.9, z1 + 2.1)
    window("F1-Window-Office-2", "window office (south, east)", "F1-Office", (8.0, 0), (10.0, 0),
           z1 + 0.9, z1 + 2.1)
    window("F1-Window-D", "window room D (north, under the sloped roof)", "F1-RoomD", (10.5, 10),
           (8.5, 10), z1 + 0.9, z1 + 1.9)
    return cells, openings


# --- geometry --------------------------------------------------------------------------------

EPS = 1e-9


def along(p, q, point):
    """(s, distance off the line) of a 2D point relative to the segment p -> q."""
    dx, dy = q[0] - p[0], q[1] - p[1]
    length = math.hypot(dx, dy)
    ux, uy = dx / length, dy / length
    rx, ry = point[0] - p[0], point[1] - p[1]
    return rx * ux + ry * uy, abs(rx * uy - ry * ux)


def wall_rings(cell, p, q, openings):
    """Outer ring and interior rings of the wall of `cell` on footprint edge p -> q, as 3D points.

    In wall coordinates (s along p -> q, z up) the outer ring runs counter-clockwise: along the
    floor, up, back along the ceiling. Seen from outside, e_s x e_z is the outward normal of a
    counter-clockwise footprint, so the ring is oriented outward."""
    length = math.hypot(q[0] - p[0], q[1] - p[1])

    def point(s, z):
        t = s / length
        return (p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1]), z)

    def floor_at(s):
        x, y, _ = point(s, 0.0)
        return cell.floor_z(x, y)

    def ceiling_at(s):
        x, y, _ = point(s, 0.0)
        return cell.ceiling_z(x, y)

    # Floor breakpoints along the wall (the stair's profile), in s.
    bottom = [0.0, length]
    if cell.floor_profile:
        for x_break, _ in cell.floor_profile:
            if abs(q[0] - p[0]) > EPS:
                s = (x_break - p[0]) / (q[0] - p[0]) * length
                if EPS < s < length - EPS:
                    bottom.append(s)
    bottom.sort()

    notches, holes = [], []
    for op in openings:
        s_a, off_a = along(p, q, op.p0)
        s_b, off_b = along(p, q, op.p1)
        if off_a > 1e-6 or off_b > 1e-6:
            continue
        lo, hi = min(s_a, s_b), max(s_a, s_b)
        if lo < -1e-6 or hi > length + 1e-6:
            continue
        if abs(op.z0 - floor_at(lo)) < 1e-6 and abs(op.z0 - floor_at(hi)) < 1e-6:
            notches.append((lo, hi, op.z1))
        else:
            holes.append((lo, hi, op.z0, op.z1))
    notches.sort()

    outer = []
    stops = sorted(set(bottom + [s for n in notches for s in n[:2]]))
    for s in stops:
        inside_notch = [n for n in notches if n[0] < s < n[1]]
        if inside_notch:
            continue
        notch_ends_here = [n for n in notches if abs(n[1] - s) < EPS]
        notch_starts_here = [n for n in notches if abs(n[0] - s) < EPS]
        if notch_ends_here:  # leaving a notch: come down its right jamb
            outer.append(point(s, notch_ends_here[0][2]))
        outer.append(point(s, floor_at(s)))
        if notch_starts_here:  # entering a notch: go up its left jamb
            outer.append(point(s, notch_starts_here[0][2]))
    outer.append(point(length, ceiling_at(length)))
    outer.append(point(0.0, ceiling_at(0.0)))

    interior = []
    for lo, hi, z0, z1 in sorted(holes):
        # Interior rings run clockwise in wall coordinates (opposite to the exterior).
        interior.append([point(lo, z0), point(lo, z1), point(hi, z1), point(hi, z0)])
    return outer, interior


def cell_polygons(cell, openings):
    """(suffix, outer ring, interior rings) of every shell polygon, oriented outward."""
    polygons = []
    fp = cell.footprint
    if cell.floor_profile:
        ys = [y for _, y in fp]
        y_lo, y_hi = min(ys), max(ys)
        profile = cell.floor_profile
        for i, ((xa, za), (xb, zb)) in enumerate(zip(profile, profile[1:])):
            up = [(xa, y_lo, za), (xb, y_lo, zb), (xb, y_hi, zb), (xa, y_hi, za)]
            polygons.append((f"floor-{i}", list(reversed(up)), []))
    else:
        polygons.append(("floor", [(x, y, cell.floor_z(x, y)) for x, y in reversed(fp)], []))
    polygons.append(("ceiling", [(x, y, cell.ceiling_z(x, y)) for x, y in fp], []))
    mine = [op for op in openings if cell.id in op.cells]
    for i in range(len(fp)):
        outer, interior = wall_rings(cell, fp[i], fp[(i + 1) % len(fp)], mine)
        polygons.append((f"wall-{i}", outer, interior))
    return polygons


def opening_ring(opening, cells_by_id):
    """Rectangle of an opening; normal from its first cell towards its second (or outward)."""
    (x0, y0), (x1, y1) = opening.p0, opening.p1
    ring = [(x0, y0, opening.z0), (x1, y1, opening.z0), (x1, y1, opening.z1),
            (x0, y0, opening.z1)]
    normal = (y1 - y0, -(x1 - x0))  # right of p0 -> p1, horizontal
    cx, cy = cells_by_id[opening.cells[0]].centroid_xy()
    mx, my = (x0 + x1) / 2, (y0 + y1) / 2
    if normal[0] * (mx - cx) + normal[1] * (my - cy) < 0:  # must point away from the first cell
        ring = [ring[1], ring[0], ring[3], ring[2]]
    return ring


# --- XML -------------------------------------------------------------------------------------

NS = {
    "core": "http://www.opengis.net/indoorgml/1.0/core",
    "navi": "http://www.opengis.net/indoorgml/1.0/navigation",
    "gml": "http://www.opengis.net/gml/3.2",
    "xlink": "http://www.w3.org/1999/xlink",
    "xsi": "http://www.w3.org/2001/XMLSchema-instance",
}


class Writer:
    def __init__(self):
        self.lines = []
        self.depth = 0

    def open(self, tag, attrs=""):
        self.lines.append("  " * self.depth + f"<{tag}{attrs}>")
        self.depth += 1

    def close(self, tag):
        self.depth -= 1
        self.lines.append("  " * self.depth + f"</{tag}>")

    def leaf(self, tag, text=None, attrs=""):
        pad = "  " * self.depth
        if text is None:
            self.lines.append(f"{pad}<{tag}{attrs}/>")
        else:
            self.lines.append(f"{pad}<{tag}{attrs}>{escape(text)}</{tag}>")

    def ring(self, tag, ident, points):
        closed = list(points) + [points[0]]
        self.open(tag)
        self.open("gml:LinearRing", f' gml:id="{ident}"')
        self.leaf("gml:posList", pos_text(closed), ' srsDimension="3"')
        self.close("gml:LinearRing")
        self.close(tag)

    def polygon(self, ident, outer, interior):
        self.open("gml:Polygon", f' gml:id="{ident}"')
        self.ring("gml:exterior", f"{ident}-ext", outer)
        for k, hole in enumerate(interior):
            self.ring("gml:interior", f"{ident}-int{k}", hole)
        self.close("gml:Polygon")


def escape(text):
    return text.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")


HEADER_COMMENT = """<!--
  conicloc example building (IndoorGML 1.0.3). GENERATED by scripts/make_example_building.py;
  do not edit by hand, re-run the script.

  Two storeys, about 18 m x 10 m, local metric coordinates (x east, y north, z up, no CRS):
    floor 0 (z 0..3.0): rooms A, B, C, D and a corridor;
    floor 1 (z 3.2..6.2): open-plan office, rooms C and D (D under a roof sloping 3.0 -> 2.2 m),
    and a corridor; a staircase (TransitionSpace, z 0..6.2, 37 deg flight) joins the storeys.
  The east facade is slanted at 30 deg to the y axis (a non-Manhattan wall).
  Doors (0.9 m x 2.1 m) are notches in the walls and navi:ConnectionBoundary polygons, each dual
  to a Transition; the entrance is a navi:AnchorBoundary; windows are interior rings of exterior
  walls and core:CellSpaceBoundary polygons.
  Thin walls: adjacent cells share wall planes. Shell polygons are oriented OUTWARD (normals point
  away from the cell interior). Rings are closed; positions are gml:posList srsDimension="3".
-->"""


def write_document(cells, openings):
    cells_by_id = {c.id: c for c in cells}
    transitions = {}  # door id -> transition id
    for op in openings:
        if op.kind == "door":
            transitions[op.id] = "T-" + op.id
        for cid in op.cells:
            cells_by_id[cid].boundaries.append(op.id)

    xs = [x for c in cells for x, _ in c.footprint]
    ys = [y for c in cells for _, y in c.footprint]
    z_top = STOREY_Z[-1] + CLEAR_HEIGHT_M

    w = Writer()
    w.lines.append('<?xml version="1.0" encoding="UTF-8"?>')
    w.lines.append(HEADER_COMMENT)
    namespaces = " ".join(f'xmlns:{p}="{u}"' for p, u in NS.items())
    schema = ("http://www.opengis.net/indoorgml/1.0/core "
              "http://schemas.opengis.net/indoorgml/1.0/indoorgmlcore.xsd "
              "http://www.opengis.net/indoorgml/1.0/navigation "
              "http://schemas.opengis.net/indoorgml/1.0/indoorgmlnavi.xsd")
    w.open("core:IndoorFeatures", f' {namespaces} xsi:schemaLocation="{schema}" gml:id="IFs"')
    w.leaf("gml:name", "conicloc example building")
    w.open("gml:boundedBy")
    w.open("gml:Envelope", ' srsDimension="3"')
    w.leaf("gml:lowerCorner", pos_text([(min(xs), min(ys), 0.0)]))
    w.leaf("gml:upperCorner", pos_text([(max(xs), max(ys), z_top)]))
    w.close("gml:Envelope")
    w.close("gml:boundedBy")

    w.open("core:primalSpaceFeatures")
    w.open("core:PrimalSpaceFeatures", ' gml:id="PSF"')
    for cell in cells:
        tag = f"{cell.cls[0]}:{cell.cls[1]}"
        w.open("core:cellSpaceMember")
        w.open(tag, f' gml:id="{cell.id}"')
        w.leaf("gml:description", cell.description)
        w.leaf("gml:name", cell.name)
        w.open("core:cellSpaceGeometry")
        w.open("core:Geometry3D")
        w.open("gml:Solid", f' gml:id="{cell.id}-solid"')
        w.open("gml:exterior")
        w.open("gml:Shell")
        for suffix, outer, interior in cell_polygons(cell, openings):
            w.open("gml:surfaceMember")
            w.polygon(f"{cell.id}-{suffix}", outer, interior)
            w.close("gml:surfaceMember")
        w.close("gml:Shell")
        w.close("gml:exterior")
        w.close("gml:Solid")
        w.close("core:Geometry3D")
        w.close("core:cellSpaceGeometry")
        w.leaf("core:duality", attrs=f' xlink:href="#S-{cell.id}"')
        for b in cell.boundaries:
            w.leaf("core:partialboundedBy", attrs=f' xlink:href="#{b}"')
        w.close(tag)
        w.close("core:cellSpaceMember")

    boundary_class = {"door": "navi:ConnectionBoundary", "entrance": "navi:AnchorBoundary",
                      "window": "core:CellSpaceBoundary"}
    for op in openings:
        tag = boundary_class[op.kind]
        w.open("core:cellSpaceBoundaryMember")
        w.open(tag, f' gml:id="{op.id}"')
        w.leaf("gml:description", op.kind)
        w.leaf("gml:name", op.name)
        if op.id in transitions:
            w.leaf("core:duality", attrs=f' xlink:href="#{transitions[op.id]}"')
        w.open("core:cellSpaceBoundaryGeometry")
        w.open("core:geometry3D")
        w.polygon(f"{op.id}-polygon", opening_ring(op, cells_by_id), [])
        w.close("core:geometry3D")
        w.close("core:cellSpaceBoundaryGeometry")
        w.close(tag)
        w.close("core:cellSpaceBoundaryMember")
    w.close("core:PrimalSpaceFeatures")
    w.close("core:primalSpaceFeatures")

    doors = [op for op in openings if op.kind == "door"]
    w.open("core:multiLayeredGraph")
    w.open("core:MultiLayeredGraph", ' gml:id="MLG"')
    w.open("core:spaceLayers", ' gml:id="SLs"')
    w.open("core:spaceLayerMember")
    w.open("core:SpaceLayer", ' gml:id="TopographicLayer"')
    w.open("core:nodes", ' gml:id="Nodes"')
    for cell in cells:
        w.open("core:stateMember")
        w.open("core:State", f' gml:id="S-{cell.id}"')
        w.leaf("gml:name", cell.name + ("" if cell.id == "Stair" else f" (floor {cell.storey})"))
        w.leaf("core:duality", attrs=f' xlink:href="#{cell.id}"')
        for op in doors:
            if cell.id in op.cells:
                w.leaf("core:connects", attrs=f' xlink:href="#{transitions[op.id]}"')
        w.open("core:geometry")
        w.open("gml:Point", f' gml:id="S-{cell.id}-point"')
        w.leaf("gml:pos", pos_text([cell.state_point()]), ' srsDimension="3"')
        w.close("gml:Point")
        w.close("core:geometry")
        w.close("core:State")
        w.close("core:stateMember")
    w.close("core:nodes")
    w.open("core:edges", ' gml:id="Edges"')
    for op in doors:
        a, b = (cells_by_id[c] for c in op.cells)
        pa, pb = a.state_point(), b.state_point()
        cx, cy, _ = op.center()
        through = (cx, cy, op.z0 + STATE_HEIGHT_M)
        line = [pa, through, pb]
        length = sum(math.dist(u, v) for u, v in zip(line, line[1:]))
        tid = transitions[op.id]
        w.open("core:transitionMember")
        w.open("core:Transition", f' gml:id="{tid}"')
        w.leaf("gml:name", op.name)
        w.leaf("core:weight", fmt(length))
        w.leaf("core:connects", attrs=f' xlink:href="#S-{a.id}"')
        w.leaf("core:connects", attrs=f' xlink:href="#S-{b.id}"')
        w.leaf("core:duality", attrs=f' xlink:href="#{op.id}"')
        w.open("core:geometry")
        w.open("gml:LineString", f' gml:id="{tid}-line"')
        w.leaf("gml:posList", pos_text(line), ' srsDimension="3"')
        w.close("gml:LineString")
        w.close("core:geometry")
        w.close("core:Transition")
        w.close("core:transitionMember")
    w.close("core:edges")
    w.close("core:SpaceLayer")
    w.close("core:spaceLayerMember")
    w.close("core:spaceLayers")
    w.close("core:MultiLayeredGraph")
    w.close("core:multiLayeredGraph")
    w.close("core:IndoorFeatures")
    return "\n".join(w.lines) + "\n"


def check(path):
    """Well-formed XML, unique gml:ids, every xlink resolves, every ring closed and planar."""
    root = ET.parse(path).getroot()
    gml_id = "{%s}id" % NS["gml"]
    href = "{%s}href" % NS["xlink"]
    ids = [e.get(gml_id) for e in root.iter() if e.get(gml_id) is not None]
    assert len(ids) == len(set(ids)), "duplicate gml:id"
    known = set(ids)
    for e in root.iter():
        target = e.get(href)
        if target is not None:
            assert target.startswith("#") and target[1:] in known, f"broken xlink {target}"
    polygons = list(root.iter("{%s}Polygon" % NS["gml"]))
    for poly in polygons:
        for pl in poly.iter("{%s}posList" % NS["gml"]):
            values = [float(v) for v in pl.text.split()]
            pts = [tuple(values[i:i + 3]) for i in range(0, len(values), 3)]
            assert pts[0] == pts[-1], f"unclosed ring in {poly.get(gml_id)}"
            assert len(pts) >= 4, f"short ring in {poly.get(gml_id)}"
    return len(polygons)


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    default = os.path.normpath(os.path.join(here, "..", "examples", "example_building.gml"))
    out = sys.argv[1] if len(sys.argv) > 1 else default
    cells, openings = building()
    text = write_document(cells, openings)
    with open(out, "w", encoding="utf-8", newline="\n") as f:
        f.write(text)
    n_polygons = check(out)
    print(f"wrote {out}: {len(cells)} cells, {len(openings)} boundaries, {n_polygons} polygons, "
          f"{len(text.encode())} bytes")


if __name__ == "__main__":
    main()
