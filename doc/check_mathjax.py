#!/usr/bin/env python3
"""Checks that the manual's formulas render offline. Used by the CMake target `doc` after doxygen,
doc/check_reference.py and the copy of MathJax into the HTML.

Opens the main page of the manual (index.html) and every other page that has a formula, from file://,
in headless chromium with the network cut off (no name resolves, every connection goes to a dead proxy),
and reads the DOM once MathJax has run. A page fails when
  1. it loads MathJax from anywhere but a copy inside the HTML directory (the manual must work offline);
  2. a formula is not rendered: fewer rendered formulas than doxygen wrote (its \\( \\) and \\[ \\]), a
     formula MathJax left unprocessed, or a raw \\f$, \\f[, \\f], \\(, \\) or \\[ left in the page's text;
  3. MathJax reported an error: a TeX error (merror), a character missing from its fonts (drawn as
     text), "Math Processing Error", or a file that failed to load.
The main page must have formulas: a check of a page without any would prove nothing.
Rendered formulas are recognised for MathJax 2 (elements MathJax-Element-N-Frame of class MathJax_SVG,
MathJax, MathJax_CHTML, ...) and MathJax 3 (mjx-container), whatever the output format.
Usage: check_mathjax.py [--chromium PATH] HTML_DIR
"""
import os
import re
import shutil
import subprocess
import sys
import tempfile
from html.parser import HTMLParser

MAIN_PAGE = "index.html"
# the classes of a rendered MathJax 2 formula, per output format
RENDERED_CLASSES = {"MathJax_SVG", "MathJax", "MathJax_CHTML", "MathJax_PHTML", "MathJax_MathML",
                    "MathJax_PlainSource", "MathJax_SVG_Display"}
# text left in a page when a formula is not rendered: doxygen's source, or MathJax's input delimiters
RAW_DELIMITERS = ("\\f$", "\\f[", "\\f]", "\\f{", "\\(", "\\)", "\\[", "\\]")
VOID_ELEMENTS = {"area", "base", "br", "col", "embed", "hr", "img", "input", "link", "meta", "param",
                 "source", "track", "wbr"}
CHROMIUM_FLAGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
                  "--disable-background-networking", "--disable-component-update", "--disable-sync",
                  "--disable-extensions", "--disable-default-apps",
                  # no network: no host name resolves, and every connection goes to a port nobody listens on
                  "--host-resolver-rules=MAP * ~NOTFOUND", "--proxy-server=127.0.0.1:1",
                  "--virtual-time-budget=10000"]


def doxygen_formulas(html):
    """The formulas doxygen wrote into a page for MathJax: inline \\( ... \\) and displayed \\[ ... \\]."""
    return re.findall(r"\\\((.*?)\\\)", html, re.S) + re.findall(r"\\\[(.*?)\\\]", html, re.S)


def mathjax_source(html):
    """The src of the script that loads MathJax, or None."""
    m = re.search(r"<script[^>]*\bsrc=\"([^\"]*MathJax\.js[^\"]*)\"", html)
    if m is None:
        m = re.search(r"<script[^>]*\bsrc=\"([^\"]*(?:tex-[a-z]+|startup)\.js[^\"]*)\"", html)  # MathJax 3
    return m.group(1) if m else None


class RenderedDom(HTMLParser):
    """What MathJax left in the DOM that chromium dumped."""

    def __init__(self):
        super().__init__(convert_charrefs=True)
        self.stack = []           # (tag, kind): kind is skip, frame, glyph_text, message or None
        self.frames = {}          # MathJax 2: formula number -> rendered
        self.containers = 0       # MathJax 3: mjx-container elements
        self.scripts = []         # MathJax 2: formula numbers of the math/tex scripts (the sources)
        self.raw = []             # text with raw formula delimiters
        self.glyph_text = []      # text drawn as text inside a formula (TeX errors, missing glyphs)
        self.errors = []          # merror elements, Math Processing Error
        self.message = []         # MathJax's message box (file failed to load, ...)

    def inside(self, kind):
        return any(k == kind for _, k in self.stack)

    def handle_starttag(self, tag, attrs):
        a = {k: (v or "") for k, v in attrs}
        classes = a.get("class", "").split()
        kind = None
        frame = re.fullmatch(r"MathJax-Element-(\d+)-Frame", a.get("id", ""))
        if frame:
            self.frames[int(frame.group(1))] = (any(c in RENDERED_CLASSES for c in classes)
                                                and not any(c.endswith("_Processing") for c in classes))
            kind = "frame"
        elif tag == "mjx-container":
            self.containers += 1
            kind = "frame"
        if tag == "script":
            source = re.fullmatch(r"MathJax-Element-(\d+)", a.get("id", ""))
            if a.get("type", "").startswith("math/tex") and source:
                self.scripts.append(int(source.group(1)))
            kind = "skip"
        elif tag in ("style", "noscript", "textarea"):
            kind = "skip"
        elif tag == "text" and self.inside("frame"):
            kind = "glyph_text"
        if a.get("id") == "MathJax_Message":
            kind = "message"
        if any("merror" in c for c in classes) or a.get("data-mml-node") == "merror":
            self.errors.append("a TeX error (%s)" % (a.get("class") or "merror"))
        if tag not in VOID_ELEMENTS:
            self.stack.append((tag, kind))

    def handle_endtag(self, tag):
        for i in range(len(self.stack) - 1, -1, -1):
            if self.stack[i][0] == tag:
                del self.stack[i:]
                return

    def handle_data(self, data):
        if self.inside("skip"):
            return
        if self.inside("glyph_text"):
            self.glyph_text.append(data)
            return
        if self.inside("message"):
            self.message.append(data)
            return
        if "Math Processing Error" in data:
            self.errors.append("Math Processing Error")
        for d in RAW_DELIMITERS:
            i = data.find(d)
            if i >= 0:
                self.raw.append(" ".join(data[max(0, i - 40):i + 60].split()))
                break


def render(chromium, page):
    """The DOM of the page after its scripts ran, from headless chromium without network."""
    with tempfile.TemporaryDirectory(prefix="check_mathjax_") as profile:
        run = subprocess.run([chromium] + CHROMIUM_FLAGS + ["--user-data-dir=" + profile, "--dump-dom",
                                                            "file://" + os.path.abspath(page)],
                             stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, timeout=300)
    if run.returncode != 0 or "</html>" not in run.stdout:
        raise RuntimeError("%s failed (exit status %d):\n%s" % (chromium, run.returncode, run.stderr[-2000:]))
    return run.stdout


def check_page(chromium, html_dir, name):
    """The problems of one page (an empty list when every formula renders) and its number of formulas."""
    path = os.path.join(html_dir, name)
    with open(path, encoding="utf-8") as f:
        html = f.read()
    formulas = len(doxygen_formulas(html))
    if formulas == 0:
        return ["no formula (\\f$ ... \\f$ or \\f[ ... \\f]) in the page: nothing to check"], 0
    src = mathjax_source(html)
    if src is None:
        return ["%d formulas but no MathJax script (USE_MATHJAX in the Doxyfile)" % formulas], formulas
    if re.match(r"^([a-z][a-z0-9+.-]*:|//)", src, re.I):
        return ["MathJax is loaded from %s, not from a copy inside the manual: it needs the network "
                "(MATHJAX_RELPATH in the Doxyfile)" % src], formulas
    local = os.path.abspath(os.path.join(os.path.dirname(path), src.split("?")[0]))
    if not os.path.isfile(local) or not local.startswith(os.path.abspath(html_dir) + os.sep):
        return ["MathJax is loaded from %s, which is not a file inside %s (the target doc copies it)"
                % (src, html_dir)], formulas

    dom = RenderedDom()
    dom.feed(render(chromium, path))
    problems = []
    rendered = sum(1 for r in dom.frames.values() if r) + dom.containers
    unrendered = sorted(n for n, r in dom.frames.items() if not r)
    if unrendered:
        problems.append("%d formulas still unprocessed by MathJax (MathJax-Element-%s, ...)"
                        % (len(unrendered), unrendered[0]))
    missing = [n for n in dom.scripts if n not in dom.frames]
    if missing:
        problems.append("%d formulas found by MathJax but never typeset (MathJax-Element-%d, ...)"
                        % (len(missing), missing[0]))
    if rendered < formulas:
        problems.append("%d of the %d formulas rendered by MathJax" % (rendered, formulas))
    for snippet in dom.raw[:5]:
        problems.append("raw formula text in the page: ...%s..." % snippet)
    if len(dom.raw) > 5:
        problems.append("... and %d more raw formula texts" % (len(dom.raw) - 5))
    for e in sorted(set(dom.errors)):
        problems.append("MathJax error: %s" % e)
    glyph_text = [t.strip() for t in dom.glyph_text if t.strip()]
    if glyph_text:
        problems.append("text drawn inside formulas (a TeX error or a character missing from MathJax's "
                        "fonts): %s" % "; ".join(sorted(set(glyph_text))[:5]))
    message = " ".join("".join(dom.message).split())
    if re.search(r"fail|error", message, re.I):
        problems.append("MathJax: %s" % message)
    return problems, formulas


def main():
    args = sys.argv[1:]
    chromium = None
    if len(args) >= 2 and args[0] == "--chromium":
        chromium, args = args[1], args[2:]
    if len(args) != 1:
        print(__doc__, file=sys.stderr)
        return 2
    html_dir = args[0]
    chromium = chromium or os.environ.get("CHROMIUM") or next(
        (p for p in map(shutil.which, ("chromium", "chromium-browser", "google-chrome")) if p), None)
    if not chromium:
        print("check_mathjax.py: no chromium (scripts/install_dependencies.sh --doc installs it)", file=sys.stderr)
        return 1
    if not os.path.isfile(os.path.join(html_dir, MAIN_PAGE)):
        print("check_mathjax.py: no %s in %s" % (MAIN_PAGE, html_dir), file=sys.stderr)
        return 1

    # the main page, then every other page that has a formula
    pages = [MAIN_PAGE]
    for name in sorted(os.listdir(html_dir)):
        if name.endswith(".html") and name != MAIN_PAGE:
            with open(os.path.join(html_dir, name), encoding="utf-8") as f:
                if doxygen_formulas(f.read()):
                    pages.append(name)
    version = "?"
    mathjax = os.path.join(html_dir, "mathjax", "MathJax.js")
    if os.path.isfile(mathjax):
        with open(mathjax, encoding="utf-8", errors="replace") as f:
            m = re.search(r"MathJax\.version\s*=\s*\"([^\"]+)\"", f.read())
            version = m.group(1) if m else version

    failed = 0
    total = 0
    for name in pages:
        try:
            problems, formulas = check_page(chromium, html_dir, name)
        except (RuntimeError, subprocess.TimeoutExpired) as e:
            problems, formulas = [str(e)], 0
        total += formulas
        for p in problems:
            print("%s: %s" % (name, p), file=sys.stderr)
        if problems:
            failed += 1
        else:
            print("check_mathjax.py: %s: %d formula%s rendered" % (name, formulas, "s"[:formulas != 1]))
    if failed:
        print("check_mathjax.py: the formulas of %d of %d pages do not render offline" % (failed, len(pages)),
              file=sys.stderr)
        return 1
    print("check_mathjax.py: all %d formulas of %d pages rendered offline by MathJax %s from %s"
          % (total, len(pages), version, os.path.relpath(os.path.dirname(mathjax), html_dir) + "/"))
    return 0


if __name__ == "__main__":
    sys.exit(main())
