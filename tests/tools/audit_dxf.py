#!/usr/bin/env python3
"""Audit DXF files with ezdxf, an independent reader: exit 1 on any audit
error or fix (a file an AutoCAD- or ODA-based importer takes as it is
needs none), and on anything a laser shop would not accept (wrong version
or units, extents that do not hold the entities, a missing model or paper
space, entities other than LWPOLYLINE/CIRCLE, open cut contours,
zero-length segments or cut segments under 0.05 mm, entities out of
cutting order: engraving, then inner contours, then outlines, the sheet's
reference outline, if any, first)."""
import math
import sys

import ezdxf

bad = 0
for path in sys.argv[1:]:
    doc = ezdxf.readfile(path)
    auditor = doc.audit()
    problems = [str(e.message) for e in auditor.errors]
    problems += [f"fix: {e.message}" for e in auditor.fixes]
    if "*Model_Space" not in doc.block_records or "*Paper_Space" not in doc.block_records:
        problems.append("no model or paper space block record")
    lo, hi = doc.header.get("$EXTMIN"), doc.header.get("$EXTMAX")
    rank = {"SHEET": 0, "ENGRAVE": 1, "CUT-INNER": 2, "CUT-OUTER": 3}
    last = 0
    if doc.dxfversion < "AC1015":
        problems.append(f"version {doc.dxfversion} is older than R2000")
    if doc.header.get("$INSUNITS") != 4:
        problems.append("$INSUNITS is not 4 (mm)")
    if doc.header.get("$MEASUREMENT") != 1:
        problems.append("$MEASUREMENT is not 1 (metric)")
    for e in doc.modelspace():
        kind, layer = e.dxftype(), e.dxf.layer
        r = rank.get(layer)
        if r is None:
            problems.append(f"entity on layer {layer}")
        elif r < last:
            problems.append(f"{layer} after a later operation")
        else:
            last = r
        if kind == "CIRCLE":
            c, rad = e.dxf.center, e.dxf.radius
            box = [(c[0] - rad, c[1] - rad), (c[0] + rad, c[1] + rad)]
        elif kind == "LWPOLYLINE":
            box = [(p[0], p[1]) for p in e.get_points("xy")]
        else:
            box = []
        for x, y in box:
            if not (lo[0] - 1e-6 <= x <= hi[0] + 1e-6 and lo[1] - 1e-6 <= y <= hi[1] + 1e-6):
                problems.append(f"{kind} on {layer} outside $EXTMIN/$EXTMAX")
                break
        if kind not in ("LWPOLYLINE", "CIRCLE"):
            problems.append(f"{kind} on {layer}")
            continue
        if kind == "LWPOLYLINE":
            pts = [(p[0], p[1]) for p in e.get_points("xy")]
            closed = e.closed
            if layer.startswith("CUT") and not closed:
                problems.append(f"open cut contour on {layer}")
            n = len(pts)
            for i in range(n if closed else n - 1):
                a, b = pts[i], pts[(i + 1) % n]
                d = math.hypot(a[0] - b[0], a[1] - b[1])
                if d <= 1e-6:
                    problems.append(f"zero-length segment on {layer}")
                    break
                if layer.startswith("CUT") and d < 0.05:
                    problems.append(f"segment of {d:.4f} mm on {layer}")
                    break
    if problems:
        bad += 1
        print(f"{path}: {len(problems)} problems: {problems[:5]}")
print(f"audited {len(sys.argv) - 1} DXF files, {bad} with problems")
sys.exit(1 if bad else 0)
