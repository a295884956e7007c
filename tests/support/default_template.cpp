#include "support/default_template.h"

#include "breastfit/model/template_library.h"

namespace breastfit::test {

const std::shared_ptr<const model::RiggedModel>& default_template() {
  static const std::shared_ptr<const model::RiggedModel> m =
      std::make_shared<const model::RiggedModel>(model::load_default_template());
  return m;
}

}  // namespace breastfit::test
