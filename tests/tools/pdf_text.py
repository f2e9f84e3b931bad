"""Read a PDF with pypdf (an independent reader) and print, as JSON, its
page count, each page's size in mm and each page's extracted text.

    python3 tests/tools/pdf_text.py FILE.pdf
"""
import json
import sys

from pypdf import PdfReader


def main(path):
    reader = PdfReader(path, strict=True)
    pages = []
    for page in reader.pages:
        box = page.mediabox
        pages.append({
            "width_mm": float(box.width) * 25.4 / 72.0,
            "height_mm": float(box.height) * 25.4 / 72.0,
            "text": page.extract_text(),
        })
    json.dump({"pages": len(reader.pages), "page": pages}, sys.stdout)


if __name__ == "__main__":
    main(sys.argv[1])
