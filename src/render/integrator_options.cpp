#include "render/integrator_options.hpp"

#include <algorithm>
#include <array>
#include <stdexcept>

namespace wp {

std::string to_string(DiffuseSampling sampling) {
    switch (sampling) {
    case DiffuseSampling::Cosine:
        return "cosine";
    case DiffuseSampling::Report:
        return "report";
    }
    return "?";
}

std::string to_string(MisStrategy strategy) {
    switch (strategy) {
    case MisStrategy::Power:
        return "power";
    case MisStrategy::LightOnly:
        return "light";
    }
    return "?";
}

std::string to_string(RouletteRule rule) {
    switch (rule) {
    case RouletteRule::Auto:
        return "auto";
    case RouletteRule::Throughput:
        return "throughput";
    case RouletteRule::Mitsuba:
        return "mitsuba";
    case RouletteRule::Sqrt:
        return "sqrt";
    case RouletteRule::Relative:
        return "relative";
    }
    return "?";
}

std::string to_string(LightSampling sampling) {
    switch (sampling) {
    case LightSampling::Area:
        return "area";
    case LightSampling::SolidAngle:
        return "solid-angle";
    }
    return "?";
}

std::string to_string(Traversal traversal) {
    switch (traversal) {
    case Traversal::Auto:
        return "auto";
    case Traversal::Hierarchy:
        return "bvh";
    case Traversal::Loop:
        return "loop";
    }
    return "?";
}

std::string path_type_name(std::uint32_t type) {
    constexpr std::array<const char*, WP_PATH_TYPE_COUNT> names = {"camera", "direct", "indirect",
                                                                   "mirror", "caustic"};
    return type < names.size() ? names[type] : "?";
}

std::uint32_t parse_path_types(const std::string& list) {
    if (list == "all")
        return kAllPathTypes;
    std::uint32_t types = 0;
    std::size_t start = 0;
    while (true) {
        const std::size_t end = std::min(list.find(',', start), list.size());
        const std::string name = list.substr(start, end - start);
        std::uint32_t type = 0;
        while (type < WP_PATH_TYPE_COUNT && path_type_name(type) != name)
            ++type;
        if (type == WP_PATH_TYPE_COUNT)
            throw std::invalid_argument("unknown path type '" + name + "' in '" + list +
                                        "'; expected a comma-separated list of camera, direct, "
                                        "indirect, mirror, caustic, or 'all'");
        types |= 1u << type;
        if (end == list.size())
            return types;
        start = end + 1;
    }
}

std::string describe_path_types(std::uint32_t types) {
    if ((types & kAllPathTypes) == kAllPathTypes)
        return "all";
    std::string text;
    for (std::uint32_t type = 0; type < WP_PATH_TYPE_COUNT; ++type)
        if (types & (1u << type)) {
            if (!text.empty())
                text += ',';
            text += path_type_name(type);
        }
    return text;
}

std::string to_string(Sampler sampler) {
    switch (sampler) {
    case Sampler::Independent:
        return "independent";
    case Sampler::Sobol:
        return "sobol";
    }
    return "?";
}

std::string to_string(LaunchPlan plan) {
    switch (plan) {
    case LaunchPlan::Auto:
        return "auto";
    case LaunchPlan::Stages:
        return "stages";
    case LaunchPlan::Bounce:
        return "bounce";
    case LaunchPlan::Wave:
        return "wave";
    }
    return "?";
}

std::string to_string(ShadeOrder order) {
    switch (order) {
    case ShadeOrder::Auto:
        return "auto";
    case ShadeOrder::Arrival:
        return "arrival";
    case ShadeOrder::Sorted:
        return "sorted";
    }
    return "?";
}

std::string aov_name(std::uint32_t number) {
    static const char* const names[kAovCount] = {"albedo", "normal", "depth"};
    return number < kAovCount ? names[number] : "?";
}

std::uint32_t parse_aovs(const std::string& list) {
    const std::string expected = "expected a comma-separated list of albedo, normal, depth";
    if (list.empty())
        throw std::invalid_argument("an empty list; " + expected);
    std::uint32_t aovs = 0;
    std::size_t start = 0;
    while (true) {
        const std::size_t end = std::min(list.find(',', start), list.size());
        const std::string name = list.substr(start, end - start);
        std::uint32_t number = 0;
        while (number < kAovCount && aov_name(number) != name)
            ++number;
        if (name.empty())
            throw std::invalid_argument("an empty entry in '" + list + "'; " + expected);
        if (number == kAovCount)
            throw std::invalid_argument("unknown AOV '" + name + "' in '" + list + "'; " +
                                        expected);
        if (aovs & (1u << number))
            throw std::invalid_argument("'" + name + "' named twice in '" + list + "'");
        aovs |= 1u << number;
        if (end == list.size())
            return aovs;
        start = end + 1;
    }
}

std::string describe_aovs(std::uint32_t aovs) {
    std::string text;
    for (std::uint32_t number = 0; number < kAovCount; ++number)
        if (aovs & (1u << number)) {
            if (!text.empty())
                text += ',';
            text += aov_name(number);
        }
    return text;
}

std::string describe_estimator(const IntegratorOptions& options) {
    const std::string diffuse = to_string(options.diffuse_sampling);
    std::string text = options.next_event_estimation
                           ? diffuse + "+nee+" + to_string(options.light_sampling)
                           : diffuse + "+no-nee";
    if (options.next_event_estimation && !options.mirror_next_event)
        text += "+no-mirror-nee";
    if (options.next_event_estimation && options.light_pick == LightPick::Area)
        text += "+area-pick";
    if (options.next_event_estimation && options.mis != MisStrategy::Power)
        text += "+mis-" + to_string(options.mis);
    if (options.roulette_depth != IntegratorOptions{}.roulette_depth)
        text += "+roulette-from-" + std::to_string(options.roulette_depth);
    if (options.roulette_rule == RouletteRule::Mitsuba ||
        options.roulette_rule == RouletteRule::Sqrt ||
        options.roulette_rule == RouletteRule::Relative)
        text += "+roulette-" + to_string(options.roulette_rule);
    if (options.path_types != kAllPathTypes)
        text += "+paths=" + describe_path_types(options.path_types);
    if (options.depth_rule == DepthRule::PathLength)
        text += "+path-length-" + std::to_string(options.max_depth);
    return text;
}

} // namespace wp
