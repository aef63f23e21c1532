"""From an archive to pages: figures (:mod:`.plots`), the jinja2 report and its PDF
(:mod:`.report`, :mod:`.pdf`, :mod:`.svgslim`, :mod:`.equations`), figure exports and
animations (:mod:`.export`, :mod:`.animate`).  Reads archives only; never simulates."""
