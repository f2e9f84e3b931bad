#!/usr/bin/env python3
"""The critical load factor of a lamella OpenSees export, found by OpenSees.

Usage: python3 opensees_buckling.py SCRIPT.py [LOW HIGH [TOLERANCE]]

Linear buckling, as lamella computes it: the exported model is built with
P-Delta transformations and its first load set is applied times lambda in
one linear step (the tangent at zero axial force, so the displacements
and the axial forces are lambda times the linear solution's); a second
step of no load then factorises the tangent K + lambda*K_G of those axial
forces with a banded Cholesky (LAPACK dpbsv), which fails exactly when it
is not positive definite, that is beyond the first critical factor. (A
Newton path with P-Delta would instead follow the pre-buckling
deformation to a limit point, which a linear buckling analysis leaves
out.) P-Delta has no P-delta within an element: its factor converges from
above as the elements are subdivided, with the error falling as the
square of their length.

The factor is bracketed by doubling from 1, or by LOW and HIGH (LOW must
be stable, HIGH not), and bisected to TOLERANCE (relative, 1e-5 unless
given). Prints {"alpha_cr": ...} as JSON.
"""
import importlib.util
import json
import sys

import openseespy.opensees as ops


def stable(model, lam):
    model.build('PDelta')
    model.LOAD_SETS[0]()
    ops.constraints('Plain')
    ops.numberer('RCM')
    ops.system('BandSPD')
    ops.algorithm('Linear')
    ops.integrator('LoadControl', lam)
    ops.analysis('Static')
    if ops.analyze(1) != 0:
        sys.exit('the linear step failed: the model is not positive definite')
    ops.integrator('LoadControl', 0.0)
    return ops.analyze(1) == 0


def main():
    if len(sys.argv) not in (2, 4, 5):
        sys.exit('usage: python3 opensees_buckling.py SCRIPT.py [LOW HIGH [TOLERANCE]]')
    spec = importlib.util.spec_from_file_location('exported', sys.argv[1])
    model = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(model)
    ops.logFile('/dev/null', '-noEcho')
    tolerance = float(sys.argv[4]) if len(sys.argv) == 5 else 1e-5
    if len(sys.argv) >= 4:
        lo, hi = float(sys.argv[2]), float(sys.argv[3])
        if not stable(model, lo) or stable(model, hi):
            sys.exit(f'the critical factor is not between {lo} and {hi}')
    else:
        lo, hi = 0.0, 1.0
        while stable(model, hi):
            lo, hi = hi, 2.0 * hi
            if hi > 1e12:
                sys.exit('no critical factor below 1e12')
    while hi - lo > tolerance * hi:
        mid = 0.5 * (lo + hi)
        if stable(model, mid):
            lo = mid
        else:
            hi = mid
    print(json.dumps({'alpha_cr': 0.5 * (lo + hi)}))


if __name__ == '__main__':
    main()
