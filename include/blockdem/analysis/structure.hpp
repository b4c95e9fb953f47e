#pragma once
// What a study (analysis/study.hpp) needs to know of a structure, whatever made it: the vault's generator, a model
// file (io/model_file.hpp), a user's code. The blocks (model::Model, rigid or meshed, with ties), the groups they
// belong to, the joint law and the contact-point grid of every pair of groups (3DEC's group-pair tables; they also
// hold for contacts that form later), the named monitor points, and the base block (the shake table) whose motion
// the histories and maps are relative to. A group is also what the report counts damage by: the vault's groups are
// its components (vault, infill, piers, slab, ...).

#include <algorithm>
#include <cstddef>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "blockdem/contact/laws.hpp"
#include "blockdem/core/error.hpp"
#include "blockdem/core/number_text.hpp"
#include "blockdem/model/contact_detection.hpp"
#include "blockdem/model/model.hpp"
#include "blockdem/model/monitor_point.hpp"

namespace blockdem::analysis {

/// The joint law and contact-point grid of every pair of groups, symmetric. A pair without a law is an error as
/// soon as two of its blocks touch (law() names the pair).
class LawTable {
 public:
  explicit LawTable(std::vector<std::string> groups = {}) : groups_(std::move(groups)) {
    const std::size_t n = groups_.size();
    law_.assign(n * n, std::nullopt);
    area_.assign(n * n, 0.0);
  }

  std::size_t groups() const { return groups_.size(); }
  const std::vector<std::string>& group_names() const { return groups_; }

  /// Sets the law of the joints between groups a and b (and b and a); `area` (m^2) is the largest area a contact
  /// point of such a joint carries (0: points at the corners of each face-to-face overlap only).
  void set(std::size_t a, std::size_t b, const contact::JointLaw& law, double area = 0) {
    check_index(a);
    check_index(b);
    law_[a * groups() + b] = law_[b * groups() + a] = law;
    area_[a * groups() + b] = area_[b * groups() + a] = area;
  }
  bool has(std::size_t a, std::size_t b) const { return a < groups() && b < groups() && law_[a * groups() + b].has_value(); }
  const contact::JointLaw& law(std::size_t a, std::size_t b) const {
    if (!has(a, b))
      throw InvalidArgument("no joint law for blocks of groups '" + name(a) + "' and '" + name(b) +
                            "' that touch: give the pair a law in the law table");
    return *law_[a * groups() + b];
  }
  double contact_point_area(std::size_t a, std::size_t b) const { return area_[a * groups() + b]; }

  /// The table of contact-point areas of model::ContactSettings (by joint tag = group index).
  void fill(model::ContactSettings& settings) const {
    settings.tag_count = static_cast<int>(groups());
    settings.contact_point_area_by_tag = area_;
  }

  std::string name(std::size_t g) const {
    if (g < groups()) return groups_[g];
    std::string unnamed(1, '#');  // (not "#" + std::string: GCC 12 warns, wrongly, of an overlap)
    unnamed += std::to_string(g);
    return unnamed;
  }

 private:
  void check_index(std::size_t g) const {
    if (g >= groups()) throw InvalidArgument("law table: no group " + std::to_string(g) + " (there are " + std::to_string(groups()) + ")");
  }

  std::vector<std::string> groups_;
  std::vector<std::optional<contact::JointLaw>> law_;
  std::vector<double> area_;
};

struct Structure {
  std::string name;    // for messages and the report: "LNEC cross vault", a model file's name
  model::Model model;  // block i belongs to group model.bodies.joint_tag[i]
  LawTable laws;       // the groups and their joints
  model::ContactSettings contacts;  // tolerance and the like; the kinds and grid come from the study and the laws
  std::vector<model::MonitorPoint> monitors;
  /// The base block the outputs are relative to (displacements relative to the table; maps of what the structure
  /// did, not where the table took it); none: a structure on fixed supports, outputs absolute.
  std::optional<std::size_t> table;
  /// Extra entries of report.json's "model" (key, JSON text): what made the model (the vault's kinematics, ...).
  std::vector<std::pair<std::string, std::string>> report;

  const std::vector<std::string>& groups() const { return laws.group_names(); }
  std::string group_of(std::size_t block) const { return laws.name(static_cast<std::size_t>(model.bodies.joint_tag[block])); }

  /// Throws InvalidArgument naming what is wrong: a block whose group is not in the table, a monitor point on no
  /// block, a table block that is not a base block.
  void validate() const {
    const auto& b = model.bodies;
    auto fail = [&](const std::string& what) { throw InvalidArgument(name + ": " + what); };
    if (b.size() == 0) fail("the model has no blocks");
    if (laws.groups() == 0) fail("the model has no groups");
    for (std::size_t i = 0; i < b.size(); ++i)
      if (b.joint_tag[i] < 0 || static_cast<std::size_t>(b.joint_tag[i]) >= laws.groups())
        fail("block '" + b.name[i] + "' has group " + std::to_string(b.joint_tag[i]) + ", not in 0.." + std::to_string(laws.groups() - 1));
    for (const auto& m : monitors) {
      if (m.name.empty()) fail("a monitor point has no name");
      if (m.block >= b.size()) fail("monitor point '" + m.name + "' is on block " + std::to_string(m.block) + ", which does not exist");
    }
    for (std::size_t p = 0; p < monitors.size(); ++p)
      for (std::size_t q = p + 1; q < monitors.size(); ++q)
        if (monitors[p].name == monitors[q].name) fail("two monitor points are named '" + monitors[p].name + "'");
    if (table && (*table >= b.size() || b.motion[*table] != model::Motion::base))
      fail("the table block must be a base block (moved by the excitation)");
  }
};

}  // namespace blockdem::analysis
