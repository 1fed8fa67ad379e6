#pragma once
/// @file The one entry point of the core, stoss::simulate: the run module (core/run/simulate.hpp).

#include "core/run/simulate.hpp"
