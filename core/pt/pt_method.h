// `pt` as the registry lists it (core/pipeline/method_registry.cpp).
#pragma once
#include "core/render/method.h"

namespace sst {

MethodInfo pt_method_info();

}  // namespace sst
