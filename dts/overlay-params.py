#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-2.0-only
"""Set Raspberry Pi overlay parameters on a compiled overlay, offline.

The Raspberry Pi firmware (and its dtoverlay tool) reads an overlay's
/__overrides__ node: each property there is a parameter, a list of
<phandle> "spec" pairs telling what setting it changes.  fdtoverlay knows
nothing of that, so `make dt-check` uses this to do what the firmware does
before the merge: patch the overlay, then hand it to fdtoverlay.

usage:
  overlay-params.py describe IN.dtbo
      one line a parameter: "NAME value CELL" when it takes a number (CELL:
      the number the overlay has now), "NAME flag" when it takes none
  overlay-params.py apply IN.dtbo OUT.dtbo EXPECT NAME[=VALUE]...
      sets the parameters in that order and writes the patched overlay;
      EXPECT gets one line per setting, for checking the merged tree:
        PATH PROP u CELLS...     cells of PROP
        PATH PROP s STRING       string PROP
        PATH @name NAME          the node's name
        PATH @under PATH         the node sits below that one
      where PATH is &label (the merged tree's __symbols__) or a path.

The spec forms handled are the ones this project's overlays use:
  <0>, "+N-N=N!N"          enable (+), disable (-) fragment N, or enable it
                           when the value is true (=) or false (!)
  <&n>, "prop:OFF"         the 32-bit cell at byte OFF set to the value
  <&n>, "prop:OFF=LIT"     ... set to LIT, whatever the value
  <&n>, "prop:OFF=", <&m>  ... set to a phandle (how "target" is switched)
  <&n>, "prop" / "prop=LIT" a string property; "name" renames the node
  <&n>, "prop?"            a boolean property, present when true
Anything else is refused, so a parameter this cannot check fails.
"""

import re
import struct
import sys

try:
    import libfdt
except ImportError:
    sys.exit("overlay-params: needs pylibfdt, which dtschema brings: run it "
             "with build/dtschema-venv/bin/python3 (make dt-check sets that up)")


class ParamError(Exception):
    pass


TRUE = ("", "y", "yes", "on", "true", "1")
FALSE = ("n", "no", "off", "false", "0")


def u32(data, off):
    return struct.unpack(">I", data[off:off + 4])[0]


def as_bool(name, value):
    v = value.lower()
    if v in TRUE:
        return True
    if v in FALSE:
        return False
    raise ParamError(f"{name}: '{value}' is not on/off")


def as_number(name, value):
    v = value.lower()
    if v in ("y", "yes", "on", "true"):
        return 1
    if v in ("n", "no", "off", "false"):
        return 0
    try:
        n = int(value, 0)
    except ValueError:
        raise ParamError(f"{name}: '{value}' is not a number") from None
    if not 0 <= n <= 0xffffffff:
        raise ParamError(f"{name}: {value} does not fit a 32-bit cell")
    return n


class Overlay:
    def __init__(self, path):
        with open(path, "rb") as f:
            data = f.read()
        self.fdt = libfdt.Fdt(data)
        self.fdt.resize(len(data) + 65536)
        self.expect = []

    # ---- tree helpers -------------------------------------------------
    def off(self, path):
        return self.fdt.path_offset(path)

    def path(self, off):
        return self.fdt.get_path(off)

    def children(self, path):
        off = self.off(path)
        names = []
        sub = self.fdt.first_subnode(off, libfdt.QUIET_NOTFOUND)
        while sub >= 0:
            names.append(self.fdt.get_name(sub))
            sub = self.fdt.next_subnode(sub, libfdt.QUIET_NOTFOUND)
        return names

    def props(self, path):
        off = self.off(path)
        out = {}
        p = self.fdt.first_property_offset(off, libfdt.QUIET_NOTFOUND)
        while p >= 0:
            prop = self.fdt.get_property_by_offset(p)
            out[prop.name] = bytes(prop)
            p = self.fdt.next_property_offset(p, libfdt.QUIET_NOTFOUND)
        return out

    def has(self, path):
        return self.fdt.path_offset(path, libfdt.QUIET_NOTFOUND) >= 0

    def node_by_phandle(self, name, phandle):
        off = self.fdt.node_offset_by_phandle(phandle, libfdt.QUIET_NOTFOUND)
        if off < 0:
            raise ParamError(f"{name}: phandle {phandle} is no node of the overlay")
        path = self.path(off)
        if not re.match(r"^/fragment@\d+(/(__overlay__|__dormant__)(/.*)?)?$", path):
            raise ParamError(f"{name}: {path} is outside the fragments")
        return path

    def labels(self):
        if not self.has("/__symbols__"):
            return {}
        return {k: v.rstrip(b"\0").decode()
                for k, v in self.props("/__symbols__").items()}

    def ref(self, path):
        """&label for a labelled node, for the expectations."""
        for label, p in self.labels().items():
            if p == path:
                return "&" + label
        raise ParamError(f"{path} has no label: cannot follow it into the merged tree")

    def merged_ref(self, path):
        """Where a node of a fragment's __overlay__ ends up, as a label or
        as its target's spec plus the rest of the path."""
        m = re.match(r"^(/fragment@\d+)/__overlay__(/.*)?$", path)
        if not m or m.group(2) is None:
            return self.ref(path)
        try:
            return self.ref(path)
        except ParamError:
            return self.target_spec(m.group(1)) + m.group(2)

    def target_spec(self, frag):
        props = self.props(frag)
        if "target-path" in props:
            return props["target-path"].rstrip(b"\0").decode()
        label = self.fixup_label(f"{frag}:target:0")
        if label is None:
            raise ParamError(f"{frag}: target is no label reference")
        return "&" + label

    # ---- __fixups__: references to the base tree's labels -------------
    def fixups(self):
        if not self.has("/__fixups__"):
            return {}
        return {k: [s for s in v.decode().split("\0") if s]
                for k, v in self.props("/__fixups__").items()}

    def fixup_label(self, site):
        for label, sites in self.fixups().items():
            if site in sites:
                return label
        return None

    def set_fixups(self, table):
        off = self.off("/__fixups__")
        for label, sites in table.items():
            if sites:
                self.fdt.setprop(off, label, ("\0".join(sites) + "\0").encode())
            elif label in self.props("/__fixups__"):
                self.fdt.delprop(off, label)

    def rename_paths(self, old, new):
        """Keep __symbols__, __fixups__ and __local_fixups__ pointing at a
        node that was renamed from path old to path new."""
        def moved(p):
            if p == old or p.startswith(old + "/") or p.startswith(old + ":"):
                return new + p[len(old):]
            return p
        if self.has("/__symbols__"):
            off = self.off("/__symbols__")
            for label, p in self.labels().items():
                if moved(p) != p:
                    self.fdt.setprop_str(off, label, moved(p))
        table = self.fixups()
        if table:
            self.set_fixups({k: [moved(s) for s in v] for k, v in table.items()})
        mirror = "/__local_fixups__" + old
        if self.has(mirror):
            self.fdt.set_name(self.off(mirror), new.rsplit("/", 1)[1])

    # ---- __overrides__ --------------------------------------------------
    def params(self):
        if not self.has("/__overrides__"):
            return {}
        return self.props("/__overrides__")

    def targets(self, name):
        """The (phandle, spec, cell, cell_offset) entries of a parameter."""
        data = self.params()[name]
        out = []
        i = 0
        while i < len(data):
            if i + 5 > len(data):
                raise ParamError(f"{name}: not <phandle>, \"spec\" pairs")
            ph = u32(data, i)
            end = data.find(b"\0", i + 4)
            if end < 0 or end == i + 4:
                raise ParamError(f"{name}: not <phandle>, \"spec\" pairs")
            spec = data[i + 4:end].decode()
            i = end + 1
            cell = cell_off = None
            if ph and re.fullmatch(r"[^:=?]+:\d+=", spec):
                if i + 4 > len(data):
                    raise ParamError(f"{name}: '{spec}' wants a cell after it")
                cell, cell_off = u32(data, i), i
                i += 4
            out.append((ph, spec, cell, cell_off))
        return out

    def describe(self):
        lines = []
        for name in self.params():
            kind = "flag"
            for ph, spec, cell, _ in self.targets(name):
                m = re.fullmatch(r"([^:=?]+):(\d+)", spec)
                if ph and m:
                    path = self.node_by_phandle(name, ph)
                    cells = self.cells(name, path, m.group(1), int(m.group(2)))
                    kind = f"value {cells[int(m.group(2)) // 4]}"
                    break
            lines.append(f"{name} {kind}")
        return lines

    def cells(self, name, path, prop, off):
        props = self.props(path)
        if prop not in props:
            raise ParamError(f"{name}: {path} has no property {prop}")
        raw = props[prop]
        if len(raw) % 4:
            raise ParamError(f"{name}: {path}/{prop} is not made of 32-bit cells")
        cells = list(struct.unpack(f">{len(raw) // 4}I", raw))
        if off % 4 or off // 4 >= len(cells):
            raise ParamError(f"{name}: offset {off} is outside {path}/{prop} "
                             f"({' '.join(map(str, cells))})")
        return cells

    def set_cell(self, name, path, prop, off, value):
        cells = self.cells(name, path, prop, off)
        cells[off // 4] = value
        self.fdt.setprop(self.off(path), prop, struct.pack(f">{len(cells)}I", *cells))
        return cells

    def fragment(self, name, n, on):
        frag = f"/fragment@{n}"
        if not self.has(frag):
            raise ParamError(f"{name}: no fragment {n}")
        kids = self.children(frag)
        have = "__overlay__" if "__overlay__" in kids else "__dormant__"
        if have not in kids:
            raise ParamError(f"{name}: fragment {n} has no __overlay__ or __dormant__")
        want = "__overlay__" if on else "__dormant__"
        if have != want:
            self.fdt.set_name(self.off(f"{frag}/{have}"), want)
            self.rename_paths(f"{frag}/{have}", f"{frag}/{want}")

    def expect_fragments(self):
        """What each enabled fragment sets on its target, once all is done."""
        for kid in self.children("/"):
            if not re.fullmatch(r"fragment@\d+", kid):
                continue
            ov = f"/{kid}/__overlay__"
            if not self.has(ov):
                continue
            for prop, raw in self.props(ov).items():
                if prop == "status":
                    self.expect.append(f"{self.target_spec('/' + kid)} status s "
                                       f"{raw.rstrip(bytes(1)).decode()}")

    def apply(self, name, value):
        if name not in self.params():
            raise ParamError(f"unknown parameter {name}")
        for ph, spec, cell, cell_off in self.targets(name):
            if ph == 0:
                if not re.fullmatch(r"([-+=!]\d+)+", spec):
                    raise ParamError(f"{name}: '{spec}' is no fragment switch")
                for op, n in re.findall(r"([-+=!])(\d+)", spec):
                    on = {"+": True, "-": False}.get(op)
                    if on is None:
                        on = as_bool(name, value) == (op == "=")
                    self.fragment(name, int(n), on)
                continue
            path = self.node_by_phandle(name, ph)
            self.apply_one(name, value, path, spec, cell, cell_off)

    def apply_one(self, name, value, path, spec, cell, cell_off):
        m = re.fullmatch(r"([^:=?]+):(\d+)(=(.*))?", spec)
        if m:
            prop, off, lit = m.group(1), int(m.group(2)), m.group(4)
            if cell is not None:
                self.switch_reference(name, path, prop, off, cell_off)
                return
            n = as_number(name, value if lit is None else lit)
            cells = self.set_cell(name, path, prop, off, n)
            self.expect.append(f"{self.merged_ref(path)} {prop} u "
                               f"{' '.join(map(str, cells))}")
            return
        m = re.fullmatch(r"([^:=?]+)\?", spec)
        if m:
            off = self.off(path)
            if as_bool(name, value):
                self.fdt.setprop(off, m.group(1), b"")
                self.expect.append(f"{self.merged_ref(path)} @present {m.group(1)}")
            elif m.group(1) in self.props(path):
                self.fdt.delprop(off, m.group(1))
            return
        m = re.fullmatch(r"([^:=?]+)(=(.*))?", spec)
        if not m:
            raise ParamError(f"{name}: '{spec}' is a form this check does not know")
        prop, text = m.group(1), value if m.group(3) is None else m.group(3)
        if prop == "name":
            new = path.rsplit("/", 1)[0] + "/" + text
            self.fdt.set_name(self.off(path), text)
            self.rename_paths(path, new)
            self.expect.append(f"{self.merged_ref(new)} @name {text}")
        else:
            self.fdt.setprop_str(self.off(path), prop, text)
            self.expect.append(f"{self.merged_ref(path)} {prop} s {text}")

    def switch_reference(self, name, path, prop, off, cell_off):
        """prop:OFF= followed by <&label>: point prop's cell at the base
        tree's label, which is what the firmware's phandle assignment does.
        The cell in __overrides__ is itself a fixup to that label."""
        self.cells(name, path, prop, off)
        label = self.fixup_label(f"/__overrides__:{name}:{cell_off}")
        if label is None:
            raise ParamError(f"{name}: the cell after '{prop}:{off}=' is no label reference")
        site = f"{path}:{prop}:{off}"
        table = {k: [s for s in v if s != site] for k, v in self.fixups().items()}
        table.setdefault(label, []).append(site)
        self.set_cell(name, path, prop, off, 0xffffffff)
        self.set_fixups(table)
        if prop == "target" and re.fullmatch(r"/fragment@\d+", path):
            for kid in self.children(path):
                inner = f"{path}/{kid}"
                for sub in self.children(inner):
                    try:
                        ref = self.ref(f"{inner}/{sub}")
                    except ParamError:
                        continue
                    self.expect.append(f"{ref} @under &{label}")

    def save(self, path):
        self.fdt.pack()
        with open(path, "wb") as f:
            f.write(self.fdt.as_bytearray())


def main(argv):
    try:
        if len(argv) == 3 and argv[1] == "describe":
            print("\n".join(Overlay(argv[2]).describe()))
            return 0
        if len(argv) >= 5 and argv[1] == "apply":
            ov = Overlay(argv[2])
            for arg in argv[5:]:
                name, _, value = arg.partition("=")
                ov.apply(name, value)
            ov.expect_fragments()
            ov.save(argv[3])
            with open(argv[4], "w") as f:
                f.write("".join(line + "\n" for line in ov.expect))
            return 0
    except ParamError as e:
        print(f"overlay-params: {e}", file=sys.stderr)
        return 1
    print(__doc__.split("\n\n")[1], file=sys.stderr)
    return 2


if __name__ == "__main__":
    sys.exit(main(sys.argv))
