#!/usr/bin/env python3
"""Inkscape extension: in-betweens of closed paths that cross themselves.

Select two or more closed paths (in selection order, or in stacking order),
choose the number of steps, and the extension inserts the in-betweens as a
group of paths. Every in-between is the boundary of an immersed disk,
checked exactly by immerse (docs/inkscape.md); the style is interpolated as
Inkscape's own Interpolate extension does (inkex.tween).

It uses the `immerse` Python package when Inkscape's Python can import it,
and otherwise calls the `immerse` command-line tool (on PATH, or named in
the Options tab).
"""

import json
import os
import shutil
import subprocess
import tempfile

import inkex
from inkex.bezier import cspsubdiv
from inkex.tween import StyleInterpolator

try:
    import immerse
except ImportError:  # Inkscape's bundled Python (Windows, macOS): use the binary.
    immerse = None

INSTALL = (
    "install either the immerse Python package into the Python Inkscape runs "
    "(pip install ./python from the immerse repository) or the immerse "
    "command-line tool (cargo install --path . in the repository, then put it "
    "on PATH or name it in the Options tab); see docs/inkscape.md"
)


class Inbetween(inkex.EffectExtension):
    """Insert self-overlap-aware in-betweens between the selected paths."""

    def add_arguments(self, pars):
        pars.add_argument("--tab", default="options")
        pars.add_argument("--steps", type=int, default=5, help="in-betweens per pair of keys")
        pars.add_argument("--order", default="selection", help="selection or stacking")
        pars.add_argument("--easing", default="linear")
        pars.add_argument("--path", default="rigid")
        pars.add_argument("--correspondence", default="best")
        pars.add_argument("--quality", default="delaunay")
        pars.add_argument("--style", type=inkex.Boolean, default=True, help="interpolate the style")
        pars.add_argument("--flatness", type=float, default=0.1, help="curve flattening tolerance (user units)")
        pars.add_argument("--binary", default="", help="the immerse binary (default: on PATH)")
        pars.add_argument("--engine", default="auto", help="auto, package or binary")

    # ------------------------------------------------------------ reading

    def keys(self):
        """The selected shapes, in the order asked for."""
        selected = self.svg.selection
        if self.options.order == "stacking":
            selected = selected.rendering_order()
        shapes = [e for e in selected.values() if isinstance(e, inkex.ShapeElement) and not isinstance(e, inkex.Group)]
        if len(shapes) < 2:
            raise inkex.AbortExtension(
                f"select two or more closed paths (found {len(shapes)}); the in-betweens go from each to the next"
            )
        return shapes

    def polygon(self, element):
        """The element's outline in document coordinates, curves flattened."""
        path = element.path.to_absolute().transform(element.composed_transform())
        csp = path.to_superpath()
        csp = [sub for sub in csp if len(sub) >= 2]
        if not csp:
            raise inkex.AbortExtension(f"{element.get_id()}: the path is empty")
        if len(csp) > 1:
            inkex.errormsg(f"{element.get_id()}: has {len(csp)} subpaths; only the first is used")
        first = [csp[0]]
        cspsubdiv(first, self.options.flatness)
        points = [(node[1][0], node[1][1]) for node in first[0]]
        if len(points) > 1 and points[0] == points[-1]:
            points.pop()
        return points

    # ----------------------------------------------------------- morphing

    def options_kw(self):
        o = self.options
        return {"path": o.path, "correspondence": o.correspondence, "quality": o.quality}

    def inbetweens_package(self, keys, names):
        """In-betweens of each pair of consecutive keys, by the package."""
        count = self.options.steps + 2
        try:
            if len(keys) == 2:
                tweens = [immerse.Tween(keys[0], keys[1], **self.options_kw())]
            else:
                seq = immerse.Sequence(keys, **self.options_kw())
                tweens = [seq.tween(s) for s in range(len(keys) - 1)]
            return [t.frames(count, easing=self.options.easing)[1:-1].tolist() for t in tweens]
        except immerse.NotSelfOverlapping as e:
            raise inkex.AbortExtension(self.name_keys(str(e), names)) from None
        except ValueError as e:
            raise inkex.AbortExtension(self.name_keys(str(e), names)) from None

    def inbetweens_binary(self, keys, names):
        """In-betweens of each pair of consecutive keys, by `immerse morph`."""
        binary = self.options.binary or shutil.which("immerse")
        if not binary or not os.access(binary, os.X_OK):
            raise inkex.AbortExtension(f"immerse is not available: {INSTALL}")
        out = []
        with tempfile.TemporaryDirectory() as work:
            files = []
            for k, points in enumerate(keys):
                f = os.path.join(work, f"key{k + 1}.json")
                with open(f, "w", encoding="utf-8") as fh:
                    json.dump({"name": names[k], "points": points}, fh)
                files.append(f)
            for k in range(len(keys) - 1):
                result = os.path.join(work, f"morph{k + 1}.json")
                o = self.options
                cmd = [binary, "morph", files[k], files[k + 1], "--frames", str(o.steps + 2),
                       "--easing", o.easing, "--path", o.path, "--correspondence", o.correspondence,
                       "--quality", o.quality, "--quiet", f"--json={result}"]
                run = subprocess.run(cmd, capture_output=True, text=True)
                if run.returncode != 0:
                    message = run.stderr.strip().removeprefix("immerse: ")
                    for f, name in zip(files, names):
                        message = message.replace(f, name)
                    raise inkex.AbortExtension(message or f"immerse morph exited with {run.returncode}")
                with open(result, encoding="utf-8") as fh:
                    frames = json.load(fh)["frames"]
                out.append([f["points"] for f in frames[1:-1]])
        return out

    @staticmethod
    def name_keys(message, names):
        """Messages name keys as a, b or keys[j]; name the paths instead."""
        if len(names) == 2:
            for label, name in (("a: ", names[0]), ("b: ", names[1])):
                if message.startswith(label):
                    return f"{name}: {message[len(label):]}"
        for j, name in enumerate(names):
            message = message.replace(f"keys[{j}]", name)
        return message

    # ------------------------------------------------------------ writing

    def effect(self):
        if self.options.steps < 1:
            raise inkex.AbortExtension("steps must be at least 1")
        elements = self.keys()
        names = [e.get_id() for e in elements]
        keys = [self.polygon(e) for e in elements]
        engine = self.options.engine
        if engine == "package" and immerse is None:
            raise inkex.AbortExtension(f"the immerse package is not installed in this Python: {INSTALL}")
        if immerse is not None and engine != "binary":
            segments = self.inbetweens_package(keys, names)
        else:
            segments = self.inbetweens_binary(keys, names)
        first = elements[0]
        parent = first.getparent()
        group = inkex.Group()
        group.label = "immerse in-betweens"
        # Points are in document coordinates: undo the parent's transform.
        group.transform = -parent.composed_transform()
        parent.insert(parent.index(first) + 1, group)
        count = self.options.steps + 1
        for s, frames in enumerate(segments):
            styles = StyleInterpolator(elements[s], elements[s + 1]) if self.options.style else None
            for i, points in enumerate(frames, start=1):
                path = inkex.PathElement()
                path.set("d", "M " + " L ".join(f"{x!r},{y!r}" for x, y in points) + " Z")
                path.style = styles.interpolate(i / count) if styles else elements[s].style
                path.label = f"{names[s]} → {names[s + 1]} {i}/{count}"
                group.add(path)


if __name__ == "__main__":
    Inbetween().run()
