"""Affine maps from DXF (block) coordinates to the drawing's XY plane in mm,
and the conversion of transformed circles/ellipses back to exact edges.

An :data:`Affine` is a tuple ``(a, b, c, tx, d, e, f, ty)``: the world point of
a 3-D point ``(x, y, z)`` is ``(a x + b y + c z + tx, d x + e y + f z + ty)``.
It already contains the unit factor to mm, every INSERT transform on the way
from model space (base point, scale incl. negative = mirror, rotation, OCS) and
the parallel projection onto world XY.  Composing with ezdxf's ``Matrix44``
(row-vector convention) is done by hand here: a dozen multiplications per
INSERT are cheaper than matrix objects per entity.

Circles, arcs, bulges and ellipses are all described as
``centre + U cos t + V sin t`` (3-D vectors, ``t`` in radians); under an affine
map that stays an ellipse (conjugate half-diameters ``u``, ``v`` in XY).
:func:`conic_edge` turns it back into an :class:`ArcEdge` when the image is a
circle (uniform scale, rotation, mirror) or an :class:`EllipseEdge` otherwise
(non-uniform scale, tilted OCS).  Hand-written because ezdxf's own
``virtual_entities`` path creates a Python entity per sub-element, which is
several times slower for large drawings.
"""

from __future__ import annotations

import math
from typing import Optional, Sequence, Tuple, Union

from ..model import ArcEdge, EdgeSource, EllipseEdge

Affine = Tuple[float, float, float, float, float, float, float, float]

TWO_PI = 2.0 * math.pi
#: Relative tolerance for "the image of a circle is a circle".
_CIRCLE_RTOL = 1e-9


def scale_affine(factor: float) -> Affine:
    """Uniform scale (e.g. inch -> mm), no rotation, no offset."""
    return (factor, 0.0, 0.0, 0.0, 0.0, factor, 0.0, 0.0)


def compose(t: Affine, m: Sequence[float]) -> Affine:
    """``t`` after the 3-D affine matrix ``m`` (ezdxf Matrix44 as 16 floats, row
    vectors: ``p' = p @ m``): the map block coords -> parent coords -> world XY."""
    a, b, c, tx, d, e, f, ty = t
    m00, m01, m02, _, m10, m11, m12, _, m20, m21, m22, _, m30, m31, m32, _ = m
    return (a * m00 + b * m01 + c * m02,
            a * m10 + b * m11 + c * m12,
            a * m20 + b * m21 + c * m22,
            a * m30 + b * m31 + c * m32 + tx,
            d * m00 + e * m01 + f * m02,
            d * m10 + e * m11 + f * m12,
            d * m20 + e * m21 + f * m22,
            d * m30 + e * m31 + f * m32 + ty)


def apply(t: Affine, p: Sequence[float]) -> Tuple[float, float]:
    """World XY (mm) of a 2-D or 3-D point."""
    x = p[0]
    y = p[1]
    z = p[2] if len(p) > 2 else 0.0
    return (t[0] * x + t[1] * y + t[2] * z + t[3], t[4] * x + t[5] * y + t[6] * z + t[7])


def length_scale(t: Affine) -> float:
    """Mean linear scale of ``t`` in XY (sqrt of |det|), e.g. for text heights."""
    return math.sqrt(abs(t[0] * t[5] - t[1] * t[4]))


def conic_edge(t: Affine, center: Sequence[float], u3: Sequence[float], v3: Sequence[float],
               t_start: float, span: float, src: EdgeSource
               ) -> Optional[Union[ArcEdge, EllipseEdge]]:
    """Exact edge for the curve ``center + U cos s + V sin s``, ``s`` from
    ``t_start`` over the signed ``span`` (radians; |span| = 2 pi for a full curve),
    mapped by ``t``.  None when the image degenerates to a line (curve seen
    edge-on)."""
    a, b, cz, tx, d, e, f, ty = t
    x, y, z = center[0], center[1], center[2]
    c = (a * x + b * y + cz * z + tx, d * x + e * y + f * z + ty)
    ux, uy = a * u3[0] + b * u3[1] + cz * u3[2], d * u3[0] + e * u3[1] + f * u3[2]
    vx, vy = a * v3[0] + b * v3[1] + cz * v3[2], d * v3[0] + e * v3[1] + f * v3[2]
    u, v = (ux, uy), (vx, vy)
    det = ux * vy - uy * vx
    uu = ux * ux + uy * uy
    vv = vx * vx + vy * vy
    if uu == 0.0 or vv == 0.0 or abs(det) <= 1e-12 * max(uu, vv):
        return None
    full = abs(span) >= TWO_PI - 1e-12
    uv = ux * vx + uy * vy
    if abs(uu - vv) <= _CIRCLE_RTOL * uu and abs(uv) <= _CIRCLE_RTOL * uu:
        radius = math.sqrt(uu)
        phi = math.atan2(u[1], u[0])
        if full:
            return ArcEdge(c, radius, 0.0, 360.0, src)
        if det > 0.0:
            start, sweep = phi + t_start, span
        else:  # mirrored: the parameter runs clockwise in the world
            start, sweep = phi - t_start, -span
        return ArcEdge(c, radius, math.degrees(start) % 360.0, math.degrees(sweep), src)
    # principal axes from the conjugate half-diameters u, v
    t0 = 0.5 * math.atan2(2.0 * uv, uu - vv)
    c0, s0 = math.cos(t0), math.sin(t0)
    major = (u[0] * c0 + v[0] * s0, u[1] * c0 + v[1] * s0)
    minor = (-u[0] * s0 + v[0] * c0, -u[1] * s0 + v[1] * c0)
    a_len = math.hypot(*major)
    ratio = min(math.hypot(*minor) / a_len, 1.0)
    if full:
        return EllipseEdge(c, major, ratio, 0.0, TWO_PI, src)
    if span < 0.0:  # EllipseEdge params run counter-clockwise
        t_start, span = t_start + span, -span
    if det > 0.0:
        p0 = t_start - t0
    else:
        p0 = t0 - (t_start + span)
    p0 %= TWO_PI
    return EllipseEdge(c, major, ratio, p0, p0 + span, src)


def bulge_arc(p1: Sequence[float], p2: Sequence[float], bulge: float
              ) -> Tuple[Tuple[float, float], float, float, float]:
    """Arc of a polyline bulge in the polyline's OCS: (centre, radius, start angle,
    signed sweep), angles in radians, sweep > 0 = counter-clockwise.

    DXF bulge = tan(sweep / 4); the centre lies left of the chord for a positive
    bulge (hand-written: two lines of trigonometry)."""
    dx = p2[0] - p1[0]
    dy = p2[1] - p1[1]
    chord = math.hypot(dx, dy)
    sweep = 4.0 * math.atan(bulge)
    h = (1.0 - bulge * bulge) / (4.0 * bulge)      # centre offset / chord
    cx = (p1[0] + p2[0]) * 0.5 - dy * h
    cy = (p1[1] + p2[1]) * 0.5 + dx * h
    radius = chord * (1.0 + bulge * bulge) / (4.0 * abs(bulge))
    start = math.atan2(p1[1] - cy, p1[0] - cx)
    return (cx, cy), radius, start, sweep
