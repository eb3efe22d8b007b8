// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

// Test support shared by the GoogleTest files:
//  (a) mesh builders (polygon soups, Surface_mesh, Polyhedron_3), renumbering, CGAL data meshes;
//  (b) INDEPENDENT checks of everything CONVENTIONS.md promises, recomputed from the vertex positions
//      and the connectivity only: nothing here calls the package's internals for geometry. From the
//      package we only read what it outputs (the connection x, the field, the loops, the report) and the
//      values it documents (weight, angle_defect, transport_angle), which are compared with our own.

#ifndef CGAL_TRIVIAL_CONNECTIONS_TEST_SUPPORT_H
#define CGAL_TRIVIAL_CONNECTIONS_TEST_SUPPORT_H

// in test_support/, one part each, every part including the one before:
// mesh_builders.h, independent_geometry.h, solver_checks.h, placement_and_integers.h, homology_checks.h
#include "test_support/homology_checks.h"

#endif // CGAL_TRIVIAL_CONNECTIONS_TEST_SUPPORT_H
