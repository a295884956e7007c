#pragma once
/// \file The shipped default template, loaded once per test program and shared.
#include <memory>

#include "breastfit/model/rigged_model.h"

namespace breastfit::test {

const std::shared_ptr<const model::RiggedModel>& default_template();

}  // namespace breastfit::test
