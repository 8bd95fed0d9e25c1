"""Checks the plugin's server-manager XML for what the
project asks of every proxy: documentation of the proxy and of every property,
a default and a domain for every numeric property, a menu category for
filters, factory hints with the .lvdv extension for readers and writers, and no
default that a data-driven range domain would silently replace.
Usage: python3 lint_xml.py XML_DIR"""
import glob
import os
import sys
import xml.etree.ElementTree as ET

problems = []
DATA_RANGE_DOMAINS = ("ArrayRangeDomain", "BoundsDomain", "ExtentDomain", "ContourRangeDomain")
files = sorted(glob.glob(os.path.join(sys.argv[1], "*.xml")))
for path in files:
    name = os.path.relpath(path, sys.argv[1])
    try:
        root = ET.parse(path).getroot()
    except ET.ParseError as e:
        problems.append("%s: not well-formed: %s" % (name, e))
        continue
    for group in root.iter("ProxyGroup"):
        for proxy in group:
            if proxy.tag not in ("SourceProxy", "WriterProxy", "Proxy"):
                continue
            pname = proxy.get("name")
            where = "%s: %s" % (name, pname)
            if proxy.find("Documentation") is None:
                problems.append(where + ": no Documentation")
            hints = proxy.find("Hints")
            if group.get("name") == "filters" and (hints is None or hints.find("ShowInMenu") is None):
                problems.append(where + ": filter without ShowInMenu")
            # dictionary volume readers and writers register .lvdv (.lvdvp: the parallel index);
            # other readers (meshes) register their own extensions and a distinct description
            volume = "DictionaryVolume" in proxy.get("class", "")
            if group.get("name") == "sources" and proxy.get("class", "").endswith("Reader"):
                rf = hints.find("ReaderFactory") if hints is not None else None
                exts = rf.get("extensions", "").split() if rf is not None else []
                if not exts or (volume and not set(exts) & {"lvdv", "lvdvp"}):
                    problems.append(where + ": reader without ReaderFactory extensions" + ("=lvdv or lvdvp" if volume else ""))
                elif not volume and "LVDIF" not in rf.get("file_description", ""):
                    problems.append(where + ": ReaderFactory file_description must name LVDIF (distinct from ParaView's readers)")
            if group.get("name") == "writers":
                wf = hints.find("WriterFactory") if hints is not None else None
                if wf is None or not set(wf.get("extensions", "").split()) & {"lvdv", "lvdvp"}:
                    problems.append(where + ": writer without WriterFactory extensions=lvdv or lvdvp")
            for prop in proxy:
                if prop.tag == "StringVectorProperty" and "FileName" in prop.get("name", "") \
                        and prop.get("panel_visibility") != "never" and prop.find("FileListDomain") is None \
                        and group.get("name") != "writers":
                    problems.append("%s.%s: file name without FileListDomain" % (where, prop.get("name")))
            for prop in proxy:
                if not prop.tag.endswith("Property"):
                    continue
                pw = "%s.%s" % (where, prop.get("name"))
                if prop.find("Documentation") is None:
                    problems.append(pw + ": no Documentation")
                if prop.tag in ("IntVectorProperty", "DoubleVectorProperty") and prop.get("information_only") != "1":
                    if prop.get("default_values") is None:
                        problems.append(pw + ": no default_values")
                    if not any(c.tag.endswith("Domain") for c in prop):
                        problems.append(pw + ": no domain")
                # ParaView replaces the XML default by the middle (default_mode) of a data-driven range
                # when the filter is created on updated input: an iso value of 0 became mid-range
                data_range = [c.tag for c in prop if c.tag in DATA_RANGE_DOMAINS]
                if data_range and prop.get("default_values") is not None:
                    problems.append(pw + ": %s would replace default_values %s by a value from the data"
                                    % (data_range[0], prop.get("default_values")))
                if prop.get("command") == "SetInputArrayToProcess" and prop.find("ArrayListDomain") is None:
                    problems.append(pw + ": array selection without ArrayListDomain")
print("checked %d XML files" % len(files))
for p in problems:
    print("FAIL " + p)
sys.exit(1 if problems else 0)
