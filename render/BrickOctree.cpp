#include "render/BrickOctree.h"

#include <algorithm>

#include "render/BrickPlacement.h"

namespace lucent {

namespace {

std::uint32_t idAt(glm::ivec3 at, glm::ivec3 per) {
    return std::uint32_t(at.x + per.x * (at.y + per.y * at.z));
}

} // namespace

BrickOctree::BrickOctree(const BrickBoxes& pages,
                         const std::vector<std::vector<std::optional<SampleBox>>>& boxes,
                         const std::vector<double>& worth)
    : pages_(pages), nodeAt_(boxes.size()), nodesPer_(boxes.size()),
      anyBox_(pages.brickCount(), 0) {
    const int levels = int(boxes.size());
    for (std::uint32_t b = 0; b < pages.brickCount(); ++b) {
        for (int l = 0; l < levels && !anyBox_[b]; ++l) {
            anyBox_[b] = boxes[std::size_t(l)][b].has_value();
        }
    }
    for (int l = 0; l < levels; ++l) {
        nodesPer_[std::size_t(l)] = (pages.bricksPerAxis() + (1 << l) - 1) / (1 << l);
        for (std::uint32_t b = 0; b < pages.brickCount(); ++b) {
            if (!anyBox_[b]) {
                continue;
            }
            const std::uint32_t id = idAt(pages.brickIndex(b) >> l, nodesPer_[std::size_t(l)]);
            auto [it, added] = nodeAt_[std::size_t(l)].try_emplace(id, nodes_.size());
            if (added) {
                nodes_.push_back(Node{l, id, std::nullopt, 0.0});
            }
            Node& node = nodes_[it->second];
            node.worth = std::max(node.worth, worth[b]);
            if (const auto& box = boxes[std::size_t(l)][b]) {
                if (!node.box) {
                    node.box = box;
                } else {
                    node.box->lo = glm::min(node.box->lo, box->lo);
                    node.box->hi = glm::max(node.box->hi, box->hi);
                    node.box->contributes = node.box->contributes || box->contributes;
                }
            }
        }
    }
}

std::size_t BrickOctree::nodeOf(std::uint32_t page, int level) const {
    const glm::ivec3 at = pages_.brickIndex(page) >> level;
    return nodeAt_[std::size_t(level)].at(idAt(at, nodesPer_[std::size_t(level)]));
}

std::optional<std::size_t> BrickOctree::ancestor(const Node& node, int level) const {
    const glm::ivec3 np = nodesPer_[std::size_t(node.level)];
    const glm::ivec3 at(int(node.id % std::uint32_t(np.x)),
                        int((node.id / std::uint32_t(np.x)) % std::uint32_t(np.y)),
                        int(node.id / std::uint32_t(np.x * np.y)));
    const auto& map = nodeAt_[std::size_t(level)];
    const auto it = map.find(idAt(at >> (level - node.level), nodesPer_[std::size_t(level)]));
    return it == map.end() ? std::nullopt : std::optional(it->second);
}

LevelChoice BrickOctree::choose(FilterReach reach, std::size_t texelBytes, std::size_t budget,
                                LodPolicy policy) const {
    std::vector<LodNode> tree(nodes_.size());
    std::vector<std::size_t> roots;
    for (std::size_t n = 0; n < nodes_.size(); ++n) {
        const Node& node = nodes_[n];
        tree[n].level = node.level;
        tree[n].worth = node.worth;
        tree[n].bytes =
            node.box ? volumeOf(storedBox(*node.box, node.level, reach).size) * texelBytes : 0;
        if (node.level == levels() - 1) {
            roots.push_back(n);
        }
    }
    for (std::uint32_t b = 0; b < pages_.brickCount(); ++b) {
        for (int l = 1; anyBox_[b] && l < levels(); ++l) {
            auto& children = tree[nodeOf(b, l)].children;
            const std::size_t child = nodeOf(b, l - 1);
            if (std::find(children.begin(), children.end(), child) == children.end()) {
                children.push_back(child);
            }
        }
    }
    return chooseLevels(tree, roots, budget, policy);
}

} // namespace lucent
