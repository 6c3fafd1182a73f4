#include "render/distributed/RankCommand.h"

#include <filesystem>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "core/scene/RenderDescriptionJson.h"

namespace lucent {

using nlohmann::json;

RankCommand renderCommand(std::uint64_t series, const SeriesEntry& entry,
                          const RenderDescription& description) {
    RankCommand c;
    c.kind = RankCommand::Kind::Render;
    c.series = series;
    c.seriesId = entry.id;
    c.seriesRoot = seriesRoot(entry);
    c.slices = entry.slices.size();
    c.dims = entry.geometry.dims;
    c.description = description;
    c.description.volume = nullptr;
    return c;
}

std::string seriesRoot(const SeriesEntry& entry) {
    if (entry.slices.empty()) {
        return entry.file;
    }
    std::filesystem::path common = std::filesystem::path(entry.slices.front().file).parent_path();
    for (const SliceRef& slice : entry.slices) {
        const std::filesystem::path folder = std::filesystem::path(slice.file).parent_path();
        // Shorten `common` until it is a prefix of this file's folder.
        while (!common.empty()) {
            const auto [end, _] =
                std::mismatch(common.begin(), common.end(), folder.begin(), folder.end());
            if (end == common.end()) {
                break;
            }
            common = common.parent_path();
        }
    }
    return common.string();
}

std::string encodeRankCommand(const RankCommand& c) {
    if (c.kind == RankCommand::Kind::Stop) {
        return json{{"kind", "stop"}}.dump();
    }
    return json{{"kind", "render"},
                {"series", c.series},
                {"id", c.seriesId},
                {"root", c.seriesRoot},
                {"slices", c.slices},
                {"dims", {c.dims.x, c.dims.y, c.dims.z}},
                {"description", toJson(c.description)}}
        .dump();
}

RankCommand decodeRankCommand(std::string_view text) {
    RankCommand c;
    try {
        const json j = json::parse(text);
        const std::string kind = j.at("kind").get<std::string>();
        if (kind == "stop") {
            return c;
        }
        if (kind != "render") {
            throw std::invalid_argument("rank command: unknown kind '" + kind + "'");
        }
        c.kind = RankCommand::Kind::Render;
        c.series = j.at("series").get<std::uint64_t>();
        c.seriesId = j.at("id").get<std::string>();
        c.seriesRoot = j.at("root").get<std::string>();
        c.slices = j.at("slices").get<std::uint64_t>();
        const json& dims = j.at("dims");
        c.dims = {dims.at(0).get<int>(), dims.at(1).get<int>(), dims.at(2).get<int>()};
        c.description = parseRenderDescription(j.at("description").get<std::string>());
    } catch (const json::exception& e) {
        throw std::invalid_argument(std::string("rank command: ") + e.what());
    }
    return c;
}

} // namespace lucent
