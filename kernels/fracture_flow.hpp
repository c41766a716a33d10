#pragma once
// Lubrication flow of a slightly compressible fluid on a crack's mid-surface, discretised with P1
// (vertex-centred) control volumes on triangles (docs/hydraulic-fracture.md):
//   - cubic law: the flux per unit width is q = -(w^3 / 12 mu) grad p;
//   - P1 Galerkin on a triangle of conductivity c = w^3 / (12 mu) gives K_ij = c e_i . e_j / (4 A), with e_i
//     the edge opposite corner i (e_0 = x_2 - x_1, e_1 = x_0 - x_2, e_2 = x_1 - x_0); rows sum to zero, so
//     the net outflow of vertex i is sum_j T_ij (p_i - p_j) with the edge transmissibility T_ij = -K_ij
//     (= c cot(theta_k) / 2, negative for an obtuse angle theta_k opposite the edge);
//   - storage: vertex v holds the volume sum over its triangles of A w_v / 3 (the integral of the linear
//     aperture, lumped), so the vertices' volumes add up to the crack's volume exactly;
//   - equation of state rho = rho0 (1 + (p - p0) / K_f).
#include <cstdint>
#include <span>

namespace rift::kernels {

struct FluidEos {
  double density0;      // rho0 [kg/m^3] at p0
  double pressure0;     // p0 [Pa]
  double bulk_modulus;  // K_f [Pa]
  double density(double p) const { return density0 * (1.0 + (p - pressure0) / bulk_modulus); }
};

// The pressure at which mass `m` fills a volume that depends on the pressure as V(p) = V0 + C (p - p_ref)
// (C >= 0: the walls' compliance), i.e. the root of rho(p) V(p) = m on the branch where rho V grows with
// p. Exact up to rounding (the quadratic's stable root); with C = 0 it is p0 + K_f (m / (rho0 V0) - 1).
double pressure_of_mass(const FluidEos& eos, double m, double v0, double compliance, double p_ref);

// Twice the area vector of triangle (a, b, c) and the P1 conductance entries scaled by 1/c: k[0] = K_12,
// k[1] = K_20, k[2] = K_01 for c = 1 (the off-diagonal entry of the edge opposite corner 0, 1, 2); the
// transmissibility of that edge is -c k[i]. Returns the triangle's area.
double p1_edge_coefficients(const double* x0, const double* x1, const double* x2, double k[3]);

// A crack's mid-surface triangle from a joint's six corner positions (corners 0-2 on one face, 3-5 facing
// them; kernels/joint_forces.hpp): the mid-surface corners, their openings along the mid-surface's normal
// n (pointing from the second face into the first: positive is separation) and the mid-surface's area.
struct CrackTriangle {
  double mid[3][3];
  double opening[3];
  double normal[3];  // unit
  double area;
};
CrackTriangle crack_triangle(const double* corner[6]);

}  // namespace rift::kernels
