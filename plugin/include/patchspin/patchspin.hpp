// Umbrella header of patchspin::core.
#pragma once

#include <patchspin/geometry.hpp>
#include <patchspin/models.hpp>
#include <patchspin/pressure.hpp>
#include <patchspin/step.hpp>
#include <patchspin/types.hpp>
