"""The ParaView plugin's property defaults (Apps/ParaViewPlugin/XML) against the
VTK classes' own defaults, read from a fresh instance through the lvdif Python
package: a Python or C++ user and a ParaView user with no property set must get
the same filter, except where the XML documents why not (ALLOWED below, each
also named in the property's <Documentation>). Runs without ParaView.
Usage: test_xml_defaults.py XML_DIR"""
import glob
import os
import sys
import xml.etree.ElementTree as ET

import lvdif

# (class, property): why the plugin differs (the XML's documentation says so too)
ALLOWED = {
    ("vtkChunkedMarchingCubes", "OutputMode"): "Merged in ParaView: one watertight surface to display",
    ("vtkChunkedMarchingCubes", "ComputeCornerColors"): "the Qt editor's shader arrays, unused by ParaView",
    ("vtkVolumeEditFilter", "ScriptText"): "a commented example script, which edits nothing, as the empty one",
}

problems, checked = [], 0
for path in sorted(glob.glob(os.path.join(sys.argv[1], "*.xml"))):
    for proxy in ET.parse(path).getroot().iter():
        cls = proxy.get("class")
        if proxy.tag not in ("SourceProxy", "WriterProxy") or not hasattr(lvdif, cls or ""):
            continue
        obj = getattr(lvdif, cls)()
        for prop in proxy:
            command, default = prop.get("command", ""), prop.get("default_values")
            if prop.tag not in ("IntVectorProperty", "DoubleVectorProperty", "StringVectorProperty") or \
                    default is None or not command.startswith("Set") or prop.get("information_only") == "1":
                continue
            getter = getattr(obj, "Get" + command[3:], None)
            if getter is None:
                continue  # e.g. SetInputArrayToProcess
            try:
                actual = getter()
            except TypeError:  # a vector getter that takes an output array
                n = int(prop.get("number_of_elements", "1"))
                actual = [0.0] * n
                getter(actual)
            want = default.split() if prop.tag != "StringVectorProperty" else [default]
            got = list(actual) if isinstance(actual, (list, tuple)) else [actual]
            if prop.tag == "StringVectorProperty":
                same = [str(g) if g is not None else "" for g in got] == want
            else:
                same = len(got) == len(want) and all(abs(float(g) - float(w)) <= 1e-12 * max(1.0, abs(float(w)))
                                                     for g, w in zip(got, want))
            checked += 1
            if not same and (cls, prop.get("name")) not in ALLOWED:
                problems.append("%s.%s: XML default %s, the class's %s" % (cls, prop.get("name"), want, got))
# One rule per property (docs/USER_GUIDE.md, "Band width, chunk edge, padding, compression level"), the
# same in every proxy: BandWidth >= 0 (0: no band, no upper limit); a volume's
# ChunkEdge one of the powers of two 4..256; the marching cubes' (cells) 16..256;
# Padding >= 0; a writer's CompressionLevel 1..19.
# test_volume_settings.py checks that the classes accept those limits and refuse
# beyond them.
STORAGE_EDGES = ["4", "8", "16", "32", "64", "128", "256"]
ranges = 0
for path in sorted(glob.glob(os.path.join(sys.argv[1], "*.xml"))):
    for proxy in ET.parse(path).getroot().iter():
        cls = proxy.get("class")
        if proxy.tag not in ("SourceProxy", "WriterProxy"):
            continue
        for prop in proxy:
            name = prop.get("name")
            if name == "BandWidth":
                dom = [(d.tag, d.get("min"), d.get("max")) for d in prop if d.tag.endswith("Domain")]
                want = [("DoubleRangeDomain", "0", None)]
            elif name == "Padding":
                dom = [(d.tag, d.get("min"), d.get("max")) for d in prop if d.tag.endswith("Domain")]
                want = [("DoubleRangeDomain", "0", None)]
            elif name == "CompressionLevel":
                dom = [(d.tag, d.get("min"), d.get("max")) for d in prop if d.tag.endswith("Domain")]
                want = [("IntRangeDomain", "1", "19")]
            elif name == "ChunkEdge" and cls == "vtkChunkedMarchingCubes":
                dom = [(d.tag, d.get("min"), d.get("max")) for d in prop if d.tag.endswith("Domain")]
                want = [("IntRangeDomain", "16", "256")]
            elif name == "ChunkEdge":
                dom = [(d.tag, [e.get("value") for e in d]) for d in prop if d.tag.endswith("Domain")]
                want = [("EnumerationDomain", STORAGE_EDGES)]
            else:
                continue
            ranges += 1
            if dom != want:
                problems.append("%s.%s: domain %s, the rule's %s" % (cls, name, dom, want))
print("checked %d defaults, %d band, chunk edge, padding and compression domains" % (checked, ranges))
assert ranges >= 14, ranges
for p in problems:
    print("FAIL " + p)
assert checked > 30, checked
sys.exit(1 if problems else 0)
