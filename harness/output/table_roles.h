// The variant table's facts as the pages' rules take them (reports name no variant).
#pragma once

#include "reports/variant_roles.h"

namespace cbr::harness {

reports::VariantRoles variantRoles();

}  // namespace cbr::harness
