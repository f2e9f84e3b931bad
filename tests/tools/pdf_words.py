"""Read a PDF with pypdf (an independent reader) and print, as JSON, every
text run (Tj) of every page, with where the content stream's operators
put it (cm, Tm, Td as the PDF reference defines them): its baseline start in
page mm (origin bottom left), its direction in degrees, its size in
points, whether the font is bold, and its advance width in mm (from the
standard Helvetica widths pypdf carries; bold runs are widened by the
Helvetica-Bold / Helvetica ratio of average widths, 1.07, a bound).

    python3 tests/tools/pdf_words.py FILE.pdf
"""
import json
import math
import sys

from pypdf import PdfReader
from pypdf.generic import ContentStream
from pypdf._text_extraction._layout_mode._font_widths import STANDARD_WIDTHS

MM_PER_PT = 25.4 / 72.0
HELVETICA = STANDARD_WIDTHS["Helvetica"]


def width_pt(text, size, bold):
    w = sum(HELVETICA.get(ch, 556) for ch in text) * size / 1000.0
    return w * (1.07 if bold else 1.0)


def mul(a, b):
    """Product of two PDF matrices [a b c d e f] (a then b)."""
    return [
        a[0] * b[0] + a[1] * b[2],
        a[0] * b[1] + a[1] * b[3],
        a[2] * b[0] + a[3] * b[2],
        a[2] * b[1] + a[3] * b[3],
        a[4] * b[0] + a[5] * b[2] + b[4],
        a[4] * b[1] + a[5] * b[3] + b[5],
    ]


def main(path):
    reader = PdfReader(path, strict=True)
    pages = []
    for page in reader.pages:
        runs = []
        fonts = page["/Resources"]["/Font"]
        content = ContentStream(page.get_contents(), reader)
        ctm = [1.0, 0.0, 0.0, 1.0, 0.0, 0.0]
        stack = []
        tm = tlm = [1.0, 0.0, 0.0, 1.0, 0.0, 0.0]
        font, size = "", 0.0
        for operands, op in content.operations:
            if op == b"q":
                stack.append(ctm)
            elif op == b"Q":
                ctm = stack.pop()
            elif op == b"cm":
                ctm = mul([float(v) for v in operands], ctm)
            elif op == b"BT":
                tm = tlm = [1.0, 0.0, 0.0, 1.0, 0.0, 0.0]
            elif op == b"Tf":
                font = str(fonts[operands[0]].get_object()["/BaseFont"])
                size = float(operands[1])
            elif op == b"Tm":
                tm = tlm = [float(v) for v in operands]
            elif op == b"Td":
                tlm = mul([1.0, 0.0, 0.0, 1.0, float(operands[0]), float(operands[1])], tlm)
                tm = tlm
            elif op == b"Tj":
                raw = operands[0]
                raw = raw.original_bytes if hasattr(raw, "original_bytes") else bytes(raw, "latin-1")
                text = raw.decode("cp1252", errors="replace")
                m = mul(tm, ctm)
                bold = "Bold" in font
                scale = math.hypot(m[0], m[1])
                pt = size * scale
                w = width_pt(text, size, bold)
                runs.append({
                    "text": text,
                    "x_mm": m[4] * MM_PER_PT,
                    "y_mm": m[5] * MM_PER_PT,
                    "rot_deg": math.degrees(math.atan2(m[1], m[0])),
                    "size_pt": pt,
                    "bold": bold,
                    "width_mm": w * scale * MM_PER_PT,
                })
                # The text matrix moves on by the run's advance.
                tm = mul([1.0, 0.0, 0.0, 1.0, w, 0.0], tm)
        box = page.mediabox
        pages.append({
            "width_mm": float(box.width) * MM_PER_PT,
            "height_mm": float(box.height) * MM_PER_PT,
            "runs": runs,
        })
    json.dump({"pages": len(reader.pages), "page": pages}, sys.stdout)


if __name__ == "__main__":
    main(sys.argv[1])
