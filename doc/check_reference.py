#!/usr/bin/env python3
"""Checks that the reference manual is complete. Used by the CMake target `doc` after doxygen.

Runs doxygen once more on the configured Doxyfile with EXTRACT_ALL (XML only, into a temporary
directory), so that undocumented entities show up too, and fails when
  1. a public entity of namespace CGAL::Trivial_connections (outside `internal`) has no documentation:
     classes and structs, their public members (friends included), free functions, enums and each of
     their values, typedefs, variables, and the named parameters of `parameters`;
  2. a class, struct, enum, typedef or free function of the namespace is not listed in the package
     description's classified reference pages (PackageDescription.txt), where users look for it.
doxygen's own WARN_IF_UNDOCUMENTED misses free functions of undocumented namespaces, hence this script.
Usage: check_reference.py DOXYGEN DOXYFILE PACKAGE_DESCRIPTION
"""
import os
import re
import subprocess
import sys
import tempfile
import xml.etree.ElementTree as ET

NAMESPACE = "CGAL::Trivial_connections"


def documented(element):
    """True when the element has a brief or detailed description with text in it."""
    for tag in ("briefdescription", "detaileddescription"):
        d = element.find(tag)
        if d is not None and "".join(d.itertext()).strip():
            return True
    return False


def public_scope(name):
    if not (name == NAMESPACE or name.startswith(NAMESPACE + "::")):
        return False
    return not any(part in ("internal", "tc_np") for part in name.split("::"))


def main():
    if len(sys.argv) != 4:
        print(__doc__, file=sys.stderr)
        return 2
    doxygen, doxyfile, package_description = sys.argv[1:]
    config = open(doxyfile).read()
    with tempfile.TemporaryDirectory() as out:
        overrides = ["EXTRACT_ALL=YES", "HIDE_UNDOC_MEMBERS=NO", "HIDE_UNDOC_CLASSES=NO", "GENERATE_HTML=NO",
                     "GENERATE_XML=YES", "OUTPUT_DIRECTORY=" + out, "WARNINGS=NO", "WARN_IF_UNDOCUMENTED=NO",
                     "WARN_AS_ERROR=NO", "QUIET=YES"]
        run = subprocess.run([doxygen, "-"], input=config + "\n" + "\n".join(overrides) + "\n",
                             capture_output=True, text=True)
        if run.returncode != 0:
            print("check_reference.py: doxygen failed:\n" + run.stderr, file=sys.stderr)
            return 1
        xml_dir = os.path.join(out, "xml")
        index = ET.parse(os.path.join(xml_dir, "index.xml")).getroot()
        missing_doc, listed = [], []
        for compound in index.findall("compound"):
            kind, name = compound.get("kind"), compound.findtext("name")
            if kind not in ("namespace", "class", "struct") or not public_scope(name):
                continue
            root = ET.parse(os.path.join(xml_dir, compound.get("refid") + ".xml")).getroot()
            cdef = root.find("compounddef")
            if kind != "namespace":
                if cdef.get("prot", "public") != "public":
                    continue
                if not documented(cdef):
                    missing_doc.append("%s %s" % (kind, name))
                if name.count("::") == 2:  # directly in the namespace
                    listed.append(name.split("::")[-1])
            for member in cdef.iter("memberdef"):
                mkind, mname = member.get("kind"), member.findtext("name")
                if member.get("prot") != "public" or mkind == "define":
                    continue
                # doxygen lists a namespace's members in its file compounds too; only the namespace counts
                where = name + "::" + mname
                if not documented(member):
                    missing_doc.append("%s %s (%s)" % (mkind, where, member.findtext("location/[@file]") or
                                                       member.find("location").get("file")))
                if mkind == "enum":
                    for value in member.findall("enumvalue"):
                        if not documented(value):
                            missing_doc.append("enum value %s::%s" % (where, value.findtext("name")))
                if kind == "namespace" and mkind in ("function", "enum", "typedef") and \
                        name in (NAMESPACE, NAMESPACE + "::parameters"):
                    listed.append(mname)
        description = open(package_description).read()
        missing_list = sorted({n for n in listed if not re.search(r"\b%s\b" % re.escape(n), description)})
    for entry in sorted(set(missing_doc)):
        print("undocumented: " + entry, file=sys.stderr)
    for entry in missing_list:
        print("not in %s: %s" % (os.path.basename(package_description), entry), file=sys.stderr)
    if missing_doc or missing_list:
        print("check_reference.py: the reference manual is incomplete (%d undocumented, %d not listed)"
              % (len(set(missing_doc)), len(missing_list)), file=sys.stderr)
        return 1
    print("check_reference.py: every public entity of %s is documented and listed" % NAMESPACE)
    return 0


if __name__ == "__main__":
    sys.exit(main())
