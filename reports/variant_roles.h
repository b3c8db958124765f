// The variant table's facts that the pages' rules use. renderer/variants holds them; the
// harness hands them in (reports include no renderer header and name no variant).
#pragma once

#include <algorithm>
#include <string>
#include <vector>

namespace cbr::reports {

struct VariantRole {
    std::string name;
    bool checkerboard = false;
    std::string equal_cost_with;  // the scaled variant a sweep matches it with at equal GPU time, or ""
    std::string cost_bound;       // the variant whose GPU time bounds the choice of its own setting, or ""
};

struct VariantRoles {
    std::string reference;              // timed and scored against by every other variant
    std::vector<VariantRole> variants;  // in the variant table's order

    const VariantRole* find(const std::string& name) const {
        for (const auto& v : variants)
            if (v.name == name) return &v;
        return nullptr;
    }
    // The scaled variants others are matched with at equal cost (drr), in the table's order.
    std::vector<std::string> equalCostBaselines() const {
        std::vector<std::string> out;
        for (const auto& v : variants)
            if (!v.equal_cost_with.empty() && std::find(out.begin(), out.end(), v.equal_cost_with) == out.end())
                out.push_back(v.equal_cost_with);
        return out;
    }
    // The variants matched with `scaled` at equal cost (cbr-aso, cbr-cso, taau).
    std::vector<std::string> equalCostPeers(const std::string& scaled) const {
        std::vector<std::string> out;
        for (const auto& v : variants)
            if (v.equal_cost_with == scaled) out.push_back(v.name);
        return out;
    }
    // The first variant whose setting's choice is bounded by another's time (cbr-cso), or nullptr.
    const VariantRole* bounded() const {
        for (const auto& v : variants)
            if (!v.cost_bound.empty()) return &v;
        return nullptr;
    }
};

}  // namespace cbr::reports
