#include "render/integrator_options.hpp"

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

std::string to_string(Sampler sampler) {
    switch (sampler) {
    case Sampler::Independent:
        return "independent";
    case Sampler::Sobol:
        return "sobol";
    }
    return "?";
}

std::string describe_estimator(const IntegratorOptions& options) {
    const std::string diffuse = to_string(options.diffuse_sampling);
    if (!options.next_event_estimation)
        return diffuse + "+no-nee";
    return diffuse + "+nee+" + to_string(options.light_sampling);
}

} // namespace wp
