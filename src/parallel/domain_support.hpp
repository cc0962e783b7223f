#pragma once
// What spatial domain decomposition (domains_over_ranks.hpp) supports, checked on the input
// document: anything else is refused by its JSON path, STRUCTMD_ERR_UNSUPPORTED "<path>: <what> is
// not available under domain decomposition".
#include <nlohmann/json.hpp>

namespace structmd {

void check_domain_support(const nlohmann::json& document);

}  // namespace structmd
