"""Plan view (x, y) of a network file as PNG: A red, B blue, edges black.

    python3 tests/tools/network_png.py samples/film-oculus.yaml docs/film-oculus.png

Needs PyYAML and cairosvg (pip).
"""
import yaml, sys, cairosvg
d=yaml.safe_load(open(sys.argv[1]))
pts=[p for c in d['curves'] for p in c['points']]
xs=[p[0] for p in pts]; ys=[p[1] for p in pts]
x0,x1,y0,y1=min(xs),max(xs),min(ys),max(ys)
W=800; s=W/max(x1-x0,y1-y0)
col={'A':'red','B':'blue','edge':'black'}
out=[f'<svg xmlns="http://www.w3.org/2000/svg" width="{W+20}" height="{W+20}"><rect width="100%" height="100%" fill="white"/>']
for c in d['curves']:
    pp=" ".join(f"{10+(p[0]-x0)*s:.1f},{10+(y1-p[1])*s:.1f}" for p in c['points'])
    out.append(f'<polyline points="{pp}" fill="none" stroke="{col.get(c["family"],"green")}" stroke-width="1"/>')
out.append('</svg>')
cairosvg.svg2png(bytestring="".join(out).encode(), write_to=sys.argv[2])
