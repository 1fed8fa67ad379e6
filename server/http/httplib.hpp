#pragma once
/// @file cpp-httplib, made safe to include next to Eigen.

#include <httplib.h>

// httplib.h includes <resolv.h>, which defines the macro `_res`; Eigen names parameters `_res`.
#undef _res
