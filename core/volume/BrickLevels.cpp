#include "core/volume/BrickLevels.h"

#include <cmath>
#include <queue>

#include "core/volume/BrickResidency.h"

namespace lucent {

namespace {

std::string mib(std::size_t bytes) {
    return std::to_string((bytes + (1U << 19)) >> 20) + " MiB";
}

// The nodes of `level` under the roots, and their bytes.
std::vector<std::size_t> atLevel(const std::vector<LodNode>& nodes,
                                 const std::vector<std::size_t>& roots, int level,
                                 std::size_t& bytes) {
    std::vector<std::size_t> out, next = roots;
    while (!next.empty()) {
        std::vector<std::size_t> finer;
        for (const std::size_t n : next) {
            if (nodes[n].level == level) {
                out.push_back(n);
            } else {
                finer.insert(finer.end(), nodes[n].children.begin(), nodes[n].children.end());
            }
        }
        next.swap(finer);
    }
    bytes = 0;
    for (const std::size_t n : out) {
        bytes += nodes[n].bytes;
    }
    return out;
}

} // namespace

LevelChoice chooseLevels(const std::vector<LodNode>& nodes, const std::vector<std::size_t>& roots,
                         std::size_t budget, LodPolicy policy) {
    LevelChoice out;
    if (roots.empty()) {
        return out;
    }
    const int coarsest = nodes[roots.front()].level;
    std::size_t coarse = 0;
    const std::vector<std::size_t> top = atLevel(nodes, roots, coarsest, coarse);
    if (coarse > budget) {
        throw BudgetError("the budget of " + mib(budget) + " holds not even level " +
                          std::to_string(coarsest) + ", the coarsest, which needs " + mib(coarse));
    }
    std::size_t fine = 0;
    std::vector<std::size_t> finest = atLevel(nodes, roots, 0, fine);
    if (fine <= budget) {
        out.shown = std::move(finest);
        out.bytes = fine;
        return out;
    }
    out.coarsened = "level 0 needs " + mib(fine) + "; the budget is " + mib(budget);
    if (policy == LodPolicy::Uniform) {
        for (int level = 1; level <= coarsest; ++level) {
            std::size_t bytes = 0;
            std::vector<std::size_t> shown = atLevel(nodes, roots, level, bytes);
            if (bytes <= budget) {
                out.shown = std::move(shown);
                out.bytes = bytes;
                return out;
            }
        }
    }
    // From the coarsest level, the refinement worth most for its bytes first
    // while it fits: a node's error goes with its voxel size (twice the next
    // finer level's) times its worth, and refining it halves that.
    std::vector<char> drawn(nodes.size(), 0);
    out.bytes = coarse;
    using Step = std::pair<double, std::size_t>; // worth of refining, node
    std::priority_queue<Step> queue;
    const auto gain = [&](std::size_t n) {
        std::size_t children = 0;
        for (const std::size_t c : nodes[n].children) {
            children += nodes[c].bytes;
        }
        const double extra = double(children > nodes[n].bytes ? children - nodes[n].bytes : 0);
        return nodes[n].worth * std::ldexp(1.0, 2 * nodes[n].level) / (extra + 1.0);
    };
    for (const std::size_t n : top) {
        drawn[n] = 1;
        if (coarsest > 0) {
            queue.push({gain(n), n});
        }
    }
    std::vector<Step> deferred; // did not fit; may once a refinement frees bytes
    while (!queue.empty()) {
        const Step step = queue.top();
        const std::size_t n = step.second;
        queue.pop();
        std::size_t children = 0;
        for (const std::size_t c : nodes[n].children) {
            children += nodes[c].bytes;
        }
        if (out.bytes - nodes[n].bytes + children > budget) {
            deferred.push_back(step); // this one stays; a cheaper refinement may still fit
            continue;
        }
        if (children < nodes[n].bytes) { // bytes freed: what did not fit may now
            for (const Step& d : deferred) {
                queue.push(d);
            }
            deferred.clear();
        }
        out.bytes = out.bytes - nodes[n].bytes + children;
        drawn[n] = 0;
        for (const std::size_t c : nodes[n].children) {
            drawn[c] = 1;
            if (nodes[c].level > 0) {
                queue.push({gain(c), c});
            }
        }
    }
    for (std::size_t n = 0; n < nodes.size(); ++n) {
        if (drawn[n] != 0) {
            out.shown.push_back(n);
        }
    }
    return out;
}

} // namespace lucent
