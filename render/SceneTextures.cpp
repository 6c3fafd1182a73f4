#include "render/SceneTextures.h"

#include <cmath>

namespace lucent {

bool SceneTextures::updateBricks(const BrickTable& t, std::uint64_t generation) {
    if (bricksKey_ && (generation == generation_ || *bricksKey_ == t)) {
        generation_ = generation;
        return false;
    }
    pageEntry_ = makeTexture3D(GL_RGBA32UI, t.bricksPerAxis, GL_RGBA_INTEGER, GL_UNSIGNED_INT,
                               t.entries.data());
    cellsPerAxis_ = t.cellsPerAxis;
    cellCode_ =
        makeTexture3D(GL_R8UI, cellsPerAxis_, GL_RED_INTEGER, GL_UNSIGNED_BYTE, t.codes.data());
    cellRange_ = makeTexture3D(GL_RG32F, cellsPerAxis_, GL_RG, GL_FLOAT, t.ranges.data());
    checkGl("page table and leaping cells");
    bricksKey_ = t;
    generation_ = generation;
    return true;
}

void SceneTextures::updateTables(const TransferFunction& tf, double lo, double hi, double stepRatio,
                                 bool preintegrate, int tableSize, int preintegrationSize) {
    auto key = std::tuple(tf, lo, hi, stepRatio);
    if (tableKey_ != key) {
        std::vector<glm::vec4> rows = bakeTable(tf, lo, hi, tableSize).rgba;
        rows.resize(2 * std::size_t(tableSize));
        for (int n = 0; n < tableSize; ++n) {
            glm::vec4 raw = rows[std::size_t(n)];
            rows[std::size_t(tableSize + n)] = raw;
            raw.a = raw.a <= 0.0f
                        ? 0.0f
                        : float(1.0 - std::pow(1.0 - std::min(double(raw.a), 1.0), stepRatio));
            rows[std::size_t(n)] = raw;
        }
        table_ = makeTexture2D(GL_RGBA32F, tableSize, 2);
        glTextureSubImage2D(table_.get(), 0, 0, 0, tableSize, 2, GL_RGBA, GL_FLOAT, rows.data());
        // The shader's one fetch per lookup interpolates between entries.
        glTextureParameteri(table_.get(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
        glTextureParameteri(table_.get(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        glTextureParameteri(table_.get(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        glTextureParameteri(table_.get(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
        tableKey_ = key;
    }
    if (preintegrate && preKey_ != key) {
        // A drag renders at a coarser step than the still frames around it:
        // the table of the other step is kept, not built again (3-22 ms).
        std::swap(preTable_, spareTable_);
        std::swap(preKey_, spareKey_);
    }
    if (preintegrate && preKey_ != key) {
        const PreintegrationTable pre =
            buildPreintegrationTable(tf, lo, hi, preintegrationSize, stepRatio);
        preTable_ = makeTexture2D(GL_RGBA32F, preintegrationSize, preintegrationSize);
        glTextureSubImage2D(preTable_.get(), 0, 0, 0, preintegrationSize, preintegrationSize,
                            GL_RGBA, GL_FLOAT, pre.rgba.data());
        preKey_ = std::move(key);
    }
    checkGl("transfer-function tables");
}

} // namespace lucent
