"""Joint axes from FreeCAD geometry: straight edges, circles and arcs, cylindrical and conical
faces, planar faces (the normal), datum lines and the origin axes. App side (no GUI), so macros
and tests can use it."""

import FreeCAD
import Part


def axis_of(item):
    """(point, direction) of the axis that `item` defines, as FreeCAD.Vector, or None.

    item: a Part.Edge, Part.Face or a document object (datum line, App::Line origin axis, or a
    shape with one straight or circular edge). Coordinates are global for objects; for sub-shapes
    they are those of the shape as given (FreeCAD's selection hands out placed sub-shapes)."""
    tol = Part.Precision.confusion()
    if isinstance(item, Part.Edge):
        return _edge_axis(item, tol)
    if isinstance(item, Part.Face):
        return _face_axis(item, tol)
    if hasattr(item, "isDerivedFrom"):
        if item.isDerivedFrom("App::Line"):  # origin axes: the x axis of their placement
            pl = item.getGlobalPlacement() if hasattr(item, "getGlobalPlacement") else item.Placement
            return pl.Base, pl.Rotation.multVec(FreeCAD.Vector(1, 0, 0))
        shape = getattr(item, "Shape", None)
        if shape is not None and not shape.isNull():
            from .feature import global_shape
            shape = global_shape(item)
            if len(shape.Edges) == 1:
                return _edge_axis(shape.Edges[0], tol)
            if len(shape.Faces) == 1:
                return _face_axis(shape.Faces[0], tol)
    return None


def _edge_axis(edge, tol):
    c = edge.Curve
    if isinstance(c, (Part.Line, Part.LineSegment)):
        p0, p1 = edge.Vertexes[0].Point, edge.Vertexes[-1].Point
        d = p1 - p0
        if d.Length <= tol:
            d = c.Direction
        return p0, _unit(d)
    if isinstance(c, (Part.Circle, Part.Ellipse)):
        return c.Center, _unit(c.Axis)
    return None


def _face_axis(face, tol):
    s = face.Surface
    if isinstance(s, (Part.Cylinder, Part.Cone)):
        return s.Center if isinstance(s, Part.Cylinder) else s.Apex, _unit(s.Axis)
    if isinstance(s, Part.Plane):
        return face.CenterOfMass, _unit(face.normalAt(*face.Surface.parameter(face.CenterOfMass)))
    return None


def _unit(v):
    v = FreeCAD.Vector(v)
    if v.Length > 0:
        v.normalize()
    return v
