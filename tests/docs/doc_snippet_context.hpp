// SPDX-License-Identifier: MIT
#pragma once
// What the C++ snippets of the README and docs/ take as given: the names a reader's program
// would have (its world, its boxes, its callbacks), declared so that each snippet compiles as
// written (tests/docs/extract_snippets.py). Nothing here is linked or run: the snippets are
// compiled only, so that one that drifts from the API fails the build.

#include <smb/smb.hpp>

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#if SMB_SNIPPETS_BULLET
#include <btBulletDynamicsCommon.h>
#include <smb/bullet/broadphase.hpp>
#endif
#if SMB_SNIPPETS_MPI
#include <mpi.h>
#endif

// A program's world, detector, boxes and ids.
extern smb::World3d world;
extern smb::Detector3d detector;
extern smb::PairEvents events;
extern std::vector<smb::Pair> pairs;
extern std::vector<smb::PeriodicPair> periodic;
// Grouped by type: one declaration names a group.
extern std::vector<smb::Box3d> boxes, my_boxes, my_moved_boxes, particles, triangles;
extern std::vector<smb::BoxId> ids, my_ids, terrain_ids, debris, a_ids, b_ids;
extern smb::BoxId debris_id;
extern smb::Box3d box;
extern std::vector<smb::Filter> body_filters;
extern std::vector<std::uint8_t> body_is_static;
extern smb::PairPredicate my_predicate;
extern std::array<double, 3> origin;
extern std::array<double, 3> dir;
extern smb::Ray3d sight_line;
extern std::vector<smb::RayHit<double>> hits;
extern int steps;

// A program's own functions.
std::vector<smb::Box3d> load_boxes();
void move_bodies(std::vector<smb::Box3d>& boxes);
using PairCallback = void(smb::BoxId a, smb::BoxId b);
using PairTest = bool(smb::BoxId a, smb::BoxId b);
PairCallback begin_contact, end_contact, on_contact_begin, on_contact_end;
PairTest same_body, same_ragdoll;

#if SMB_SNIPPETS_BULLET
// A Bullet program's parts, beside the broad phase it switches.
extern btDefaultCollisionConfiguration configuration;
extern btCollisionDispatcher dispatcher;
extern btSequentialImpulseConstraintSolver solver;
#endif
