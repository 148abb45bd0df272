// Umbrella header of the gencoord runtime core.
#pragma once

#include "gencoord/acceleration_jacobians.hpp"
#include "gencoord/batch.hpp"
#include "gencoord/csv_writer.hpp"
#include "gencoord/cubic_spline.hpp"
#include "gencoord/dynamics.hpp"
#include "gencoord/errors.hpp"
#include "gencoord/integrate/integrator.hpp"
#include "gencoord/integrate/simulate.hpp"
#include "gencoord/integrate/step.hpp"
#include "gencoord/inverse_dynamics.hpp"
#include "gencoord/model_traits.hpp"
#include "gencoord/scripted/model.hpp"
#include "gencoord/scripted/script.hpp"
#include "gencoord/state.hpp"
