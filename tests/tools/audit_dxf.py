#!/usr/bin/env python3
"""Audit DXF files with ezdxf, an independent reader: exit 1 on any audit
error, and on anything a laser shop would not accept (wrong version or
units, entities other than LWPOLYLINE/CIRCLE, blocks referenced, open cut
contours, zero-length segments)."""
import math
import sys

import ezdxf

bad = 0
for path in sys.argv[1:]:
    doc = ezdxf.readfile(path)
    auditor = doc.audit()
    problems = [str(e.message) for e in auditor.errors]
    if doc.dxfversion < "AC1015":
        problems.append(f"version {doc.dxfversion} is older than R2000")
    if doc.header.get("$INSUNITS") != 4:
        problems.append("$INSUNITS is not 4 (mm)")
    if doc.header.get("$MEASUREMENT") != 1:
        problems.append("$MEASUREMENT is not 1 (metric)")
    for e in doc.modelspace():
        kind, layer = e.dxftype(), e.dxf.layer
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
                if math.hypot(a[0] - b[0], a[1] - b[1]) <= 1e-6:
                    problems.append(f"zero-length segment on {layer}")
                    break
    if problems:
        bad += 1
        print(f"{path}: {len(problems)} problems: {problems[:5]}")
print(f"audited {len(sys.argv) - 1} DXF files, {bad} with problems")
sys.exit(1 if bad else 0)
