#pragma once
// How each enum of the scene is spelt in a scene file. The readers (read_*_section.cpp) go through these
// tables, and the resolved scene records the name they read; the order of a table is the order the
// diagnostics and the schema list the options in.
#include <array>

#include "engine/scene/scene.hpp"
#include "engine/scene/yaml_reader.hpp"

namespace rift::scene_names {

inline constexpr std::array<Named<NotchSpec::Shape>, 2> kNotchShape{{
    {NotchSpec::Shape::wedge, "wedge"},
    {NotchSpec::Shape::slot, "slot"},
}};

inline constexpr std::array<Named<SolidBoundarySpec::Kind>, 6> kSolidBoundary{{
    {SolidBoundarySpec::Kind::fixed, "fixed"},
    {SolidBoundarySpec::Kind::velocity, "velocity"},
    {SolidBoundarySpec::Kind::traction, "traction"},
    {SolidBoundarySpec::Kind::pressure, "pressure"},
    {SolidBoundarySpec::Kind::in_situ, "in_situ"},
    {SolidBoundarySpec::Kind::fluid_pressure, "fluid_pressure"},
}};

inline constexpr std::array<Named<FluidBoundarySpec::Kind>, 5> kFluidBoundary{{
    {FluidBoundarySpec::Kind::no_slip, "no_slip"},
    {FluidBoundarySpec::Kind::velocity, "velocity"},
    {FluidBoundarySpec::Kind::free_slip, "free_slip"},
    {FluidBoundarySpec::Kind::pressure, "pressure"},
    {FluidBoundarySpec::Kind::outflow, "outflow"},
}};

inline constexpr std::array<Named<FluidSpec::Coupling>, 2> kPressureCoupling{{
    {FluidSpec::Coupling::schur_gmres, "schur_gmres"},
    {FluidSpec::Coupling::projection, "projection"},
}};

inline constexpr std::array<Named<FluidSpec::OnPicardFailure>, 2> kOnPicardFailure{{
    {FluidSpec::OnPicardFailure::stop, "stop"},
    {FluidSpec::OnPicardFailure::continue_run, "continue"},
}};

inline constexpr std::array<Named<FluidSolidSpec::Force>, 2> kCouplingForce{{
    {FluidSolidSpec::Force::volume, "volume"},
    {FluidSolidSpec::Force::wetted_faces, "wetted_faces"},
}};

inline constexpr std::array<Named<FluidSolidSpec::Continuity>, 2> kContinuity{{
    {FluidSolidSpec::Continuity::mixture, "mixture"},
    {FluidSolidSpec::Continuity::fluid, "fluid"},
}};

inline constexpr std::array<Named<FluidSolidSpec::Coupling>, 2> kWindowCoupling{{
    {FluidSolidSpec::Coupling::sequential, "sequential"},
    {FluidSolidSpec::Coupling::concurrent, "concurrent"},
}};

inline constexpr std::array<Named<FractureFlowSpec::Solver>, 3> kNetworkSolver{{
    {FractureFlowSpec::Solver::automatic, "automatic"},
    {FractureFlowSpec::Solver::direct, "direct"},
    {FractureFlowSpec::Solver::cg, "cg"},
}};

inline constexpr std::array<Named<ReferenceMetricSpec::Reduce>, 4> kReduce{{
    {ReferenceMetricSpec::Reduce::max, "max"},
    {ReferenceMetricSpec::Reduce::min, "min"},
    {ReferenceMetricSpec::Reduce::final, "final"},
    {ReferenceMetricSpec::Reduce::max_abs, "max_abs"},
}};

}  // namespace rift::scene_names
