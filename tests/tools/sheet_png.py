#!/usr/bin/env python3
"""Render a sheet SVG to PNG for the README (cairosvg): the hairline
strokes are widened to WIDTH mm so they show at picture size; nothing else
changes. Usage: sheet_png.py SHEET.svg OUT.png [PIXELS_WIDE] [WIDTH_MM]"""
import re
import sys

import cairosvg

src, dst = sys.argv[1], sys.argv[2]
px = int(sys.argv[3]) if len(sys.argv) > 3 else 1600
width = sys.argv[4] if len(sys.argv) > 4 else "1.5"
svg = open(src, encoding="utf-8").read()
svg = re.sub(r'stroke-width="[^"]*"', f'stroke-width="{width}"', svg)
cairosvg.svg2png(bytestring=svg.encode(), write_to=dst, output_width=px, background_color="white")
