#include "harness/output/table_roles.h"

#include "renderer/variants/variants.h"

namespace cbr::harness {

reports::VariantRoles variantRoles() {
    reports::VariantRoles roles;
    roles.reference = std::string(variants::referenceVariant().name);
    for (const auto& v : variants::allVariants())
        roles.variants.push_back({std::string(v.name), v.checkerboard, std::string(v.equal_cost_with),
                                  std::string(v.cost_bound)});
    return roles;
}

}  // namespace cbr::harness
