// The hierarchical GP's model parameters and data (mocapdb/gp/hierarchical_gp.hpp): parameter
// vectors, names and validation.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "mocapdb/core/error.hpp"
#include "mocapdb/gp/hierarchical_gp.hpp"

namespace mocapdb::gp {

VecX HgpModel::noise_variance() const { return (log_noise.array().exp() + noise_floor).matrix(); }

std::size_t HgpModel::parameter_count() const {
    return child.parameter_count() + (grouped ? group.parameter_count() : 0) +
           (hierarchical ? parent.parameter_count() : 0) + static_cast<std::size_t>(log_noise.size());
}

VecX HgpModel::parameters() const {
    std::vector<double> p;
    for (const auto& t : child.terms) append_parameters(t, p);
    if (grouped)
        for (const auto& t : group.terms) append_parameters(t, p);
    if (hierarchical)
        for (const auto& t : parent.terms) append_parameters(t, p);
    for (Eigen::Index i = 0; i < log_noise.size(); ++i) p.push_back(log_noise[i]);
    return Eigen::Map<const VecX>(p.data(), static_cast<Eigen::Index>(p.size()));
}

void HgpModel::set_parameters(const VecX& p) {
    if (static_cast<std::size_t>(p.size()) != parameter_count())
        throw InvalidArgument("HgpModel::set_parameters: expected " + std::to_string(parameter_count()) +
                              " values, found " + std::to_string(p.size()));
    std::size_t o = 0;
    for (auto& t : child.terms) o = read_parameters(t, p, o);
    if (grouped)
        for (auto& t : group.terms) o = read_parameters(t, p, o);
    if (hierarchical)
        for (auto& t : parent.terms) o = read_parameters(t, p, o);
    for (Eigen::Index i = 0; i < log_noise.size(); ++i) log_noise[i] = p[static_cast<Eigen::Index>(o) + i];
}

std::vector<std::string> HgpModel::parameter_names() const {
    std::vector<std::string> names;
    auto add = [&](const Lmc& lmc, const std::string& layer) {
        for (std::size_t q = 0; q < lmc.terms.size(); ++q) {
            const auto& t = lmc.terms[q];
            const std::string pre = layer + ".q" + std::to_string(q) + ".";
            names.push_back(pre + "log_lengthscale");
            for (Eigen::Index j = 0; j < t.W.cols(); ++j)
                for (Eigen::Index i = 0; i < t.W.rows(); ++i)
                    names.push_back(pre + "W[" + std::to_string(i) + "," + std::to_string(j) + "]");
            for (Eigen::Index i = 0; i < t.log_kappa.size(); ++i)
                names.push_back(pre + "log_kappa[" + std::to_string(i) + "]");
        }
    };
    add(child, "child");
    if (grouped) add(group, "group");
    if (hierarchical) add(parent, "parent");
    for (Eigen::Index i = 0; i < log_noise.size(); ++i) names.push_back("log_noise[" + std::to_string(i) + "]");
    return names;
}

void validate(const HgpModel& model) {
    const std::size_t d = model.outputs();
    if (d == 0) throw InvalidArgument("HgpModel: no outputs (log_noise is empty)");
    if (!model.log_noise.allFinite()) throw InvalidArgument("HgpModel: non-finite log_noise");
    if (!(model.noise_floor >= 0.0) || !std::isfinite(model.noise_floor))
        throw InvalidArgument("HgpModel: noise_floor must be finite and ≥ 0");
    if (model.child.terms.empty()) throw InvalidArgument("HgpModel: the child LMC needs at least one term");
    validate(model.child, d, "child LMC");
    if (model.hierarchical) {
        if (model.parent.terms.empty()) throw InvalidArgument("HgpModel: the parent LMC needs at least one term");
        validate(model.parent, d, "parent LMC");
    }
    if (model.grouped) {
        if (!model.hierarchical) throw InvalidArgument("HgpModel: a grouped (three-layer) model must be hierarchical");
        if (model.group.terms.empty()) throw InvalidArgument("HgpModel: the group LMC needs at least one term");
        validate(model.group, d, "group LMC");
    }
}

bool HgpData::is_observed(std::size_t child, std::size_t frame) const {
    if (child >= observed.size() || observed[child].empty()) return true;
    return observed[child][frame];
}

bool HgpData::is_complete(std::size_t child) const {
    if (child >= observed.size()) return true;
    for (bool b : observed[child])
        if (!b) return false;
    return true;
}

bool HgpData::all_complete() const {
    for (std::size_t r = 0; r < children.size(); ++r)
        if (!is_complete(r)) return false;
    return true;
}

std::size_t HgpData::observed_value_count() const {
    std::size_t n = 0;
    for (std::size_t r = 0; r < children.size(); ++r)
        for (std::size_t f = 0; f < frames(); ++f)
            if (is_observed(r, f)) n += outputs();
    return n;
}

HgpData without_child(const HgpData& data, std::size_t child) {
    if (child >= data.child_count()) throw InvalidArgument("without_child: no child " + std::to_string(child));
    HgpData out;
    out.times = data.times;
    std::vector<std::size_t> kept_groups;
    for (std::size_t r = 0; r < data.child_count(); ++r) {
        if (r == child) continue;
        out.children.push_back(data.children[r]);
        if (r < data.observed.size()) {
            out.observed.resize(out.children.size());
            out.observed.back() = data.observed[r];
        }
        if (!data.groups.empty()) kept_groups.push_back(data.groups[r]);
    }
    std::vector<std::size_t> present = kept_groups;
    std::sort(present.begin(), present.end());
    present.erase(std::unique(present.begin(), present.end()), present.end());
    for (std::size_t g : kept_groups)
        out.groups.push_back(
            static_cast<std::size_t>(std::lower_bound(present.begin(), present.end(), g) - present.begin()));
    return out;
}

std::size_t HgpData::group_count() const {
    std::size_t s = 0;
    for (std::size_t g : groups) s = std::max(s, g + 1);
    return s;
}

std::size_t HgpData::balanced_group_size() const {
    const std::size_t s = group_count();
    if (s == 0) return 0;
    std::vector<std::size_t> size(s, 0);
    for (std::size_t g : groups) ++size[g];
    for (std::size_t n : size)
        if (n != size.front()) return 0;
    return size.front();
}

void validate(const HgpData& data) {
    if (data.times.size() == 0 || !data.times.allFinite())
        throw InvalidArgument("HgpData: expected ≥ 1 finite sample time");
    if (data.children.empty()) throw InvalidArgument("HgpData: no children");
    const Eigen::Index d = data.children.front().rows();
    if (d == 0) throw InvalidArgument("HgpData: children have no outputs");
    if (data.observed.size() > data.children.size())
        throw InvalidArgument("HgpData: more observation masks than children");
    for (std::size_t r = 0; r < data.children.size(); ++r) {
        const MatX& y = data.children[r];
        if (y.rows() != d || y.cols() != data.times.size())
            throw InvalidArgument("HgpData: child " + std::to_string(r) + " is " + std::to_string(y.rows()) + " by " +
                                  std::to_string(y.cols()) + ", expected " + std::to_string(d) + " by " +
                                  std::to_string(data.times.size()));
        if (r < data.observed.size() && !data.observed[r].empty() &&
            data.observed[r].size() != static_cast<std::size_t>(data.times.size()))
            throw InvalidArgument("HgpData: child " + std::to_string(r) + "'s mask has " +
                                  std::to_string(data.observed[r].size()) + " flags, expected " +
                                  std::to_string(data.times.size()));
        for (Eigen::Index f = 0; f < y.cols(); ++f)
            if (data.is_observed(r, static_cast<std::size_t>(f)) && !y.col(f).allFinite())
                throw InvalidArgument("HgpData: child " + std::to_string(r) +
                                      " has a non-finite observed value at frame " + std::to_string(f));
    }
    if (data.observed_value_count() == 0) throw InvalidArgument("HgpData: nothing is observed");
    if (!data.groups.empty()) {
        if (data.groups.size() != data.children.size())
            throw InvalidArgument("HgpData: " + std::to_string(data.groups.size()) + " group indices for " +
                                  std::to_string(data.children.size()) + " children");
        std::vector<bool> used(data.group_count(), false);
        for (std::size_t g : data.groups) used[g] = true;
        for (std::size_t g = 0; g < used.size(); ++g)
            if (!used[g])
                throw InvalidArgument("HgpData: group " + std::to_string(g) + " has no child (groups are 0..S−1)");
    }
}

}  // namespace mocapdb::gp
