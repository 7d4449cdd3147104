#include "report/convergence.hpp"

#include <algorithm>
#include <cstdio>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "image/metrics.hpp"
#include "util/file.hpp"

namespace wp {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::string number(double value) {
    if (!std::isfinite(value))
        return "nan";
    char text[64];
    std::snprintf(text, sizeof text, "%.9g", value);
    return text;
}

double parse_number(const std::string& text) {
    if (text == "nan")
        return kNaN;
    std::size_t used = 0;
    double value = std::stod(text, &used);
    if (used != text.size())
        throw std::invalid_argument("not a number");
    return value;
}

const char* const kCsvHeader =
    "estimator,width,height,spp,seconds,build_seconds,warm_up_seconds,error_source,mse,rmse,"
    "rel_mse,"
    "efficiency,rel_efficiency,mse_halves,rel_mse_halves";

} // namespace

Checkpoint measure_checkpoint(const Film& film, std::uint32_t spp, double seconds,
                              const Image* reference, std::uint32_t first_sample) {
    Checkpoint c;
    c.spp = spp;
    c.seconds = seconds;
    const Image mean = film.mean();
    // Of the samples [first, first + spp), (spp + 1) / 2 have the parity of
    // `first` and spp / 2 the other.
    const std::uint64_t same = (spp + 1u) / 2u, other = spp / 2u;
    const std::uint64_t n_even = first_sample % 2u == 0u ? same : other;
    const std::uint64_t n_odd = spp - n_even;
    if (n_odd > 0 && n_even > 0) {
        const Image even = film.half_mean(0), odd = film.half_mean(1);
        c.mse_halves = mse_from_halves(even, odd, n_even, n_odd);
        c.rel_mse_halves = rel_mse_from_halves(even, odd, n_even, n_odd);
    } else {
        c.mse_halves = c.rel_mse_halves = kNaN;
    }
    if (reference != nullptr) {
        c.against_reference = true;
        c.mse = mse(mean, *reference);
        c.rel_mse = rel_mse(mean, *reference);
    } else {
        c.mse = c.mse_halves;
        c.rel_mse = c.rel_mse_halves;
    }
    c.rmse = std::sqrt(c.mse);
    c.efficiency = 1.0 / (c.mse * seconds);
    c.rel_efficiency = 1.0 / (c.rel_mse * seconds);
    return c;
}

std::vector<std::uint32_t> checkpoint_schedule(std::uint32_t max_spp) {
    std::vector<std::uint32_t> spp;
    for (std::uint64_t n = 1; n < max_spp; n *= 2)
        spp.push_back(static_cast<std::uint32_t>(n));
    if (max_spp > 0)
        spp.push_back(max_spp);
    return spp;
}

ConvergenceRun run_convergence(WavefrontIntegrator& integrator, Film& film, const Image* reference,
                               const ConvergenceSettings& settings,
                               const std::function<void(const Checkpoint&)>& on_checkpoint) {
    if (settings.max_spp == 0 && !(settings.max_seconds > 0.0))
        throw std::invalid_argument("a convergence run needs a sample or a time limit");
    if (reference != nullptr &&
        (reference->width != integrator.width() || reference->height != integrator.height()))
        throw ImageError("the reference is " + std::to_string(reference->width) + "x" +
                         std::to_string(reference->height) + " but the render is " +
                         std::to_string(integrator.width()) + "x" +
                         std::to_string(integrator.height()));
    ConvergenceRun run;
    run.estimator = describe_estimator(integrator.options());
    run.width = integrator.width();
    run.height = integrator.height();
    run.build_seconds = integrator.program().build_seconds;
    if (settings.warm_up) {
        const double before = integrator.stats().render_seconds;
        Film scratch(integrator.width(), integrator.height());
        integrator.render(settings.first_sample, 1, scratch);
        run.warm_up_seconds = integrator.stats().render_seconds - before;
    }
    const double start_seconds = integrator.stats().render_seconds;
    std::vector<Checkpoint>& checkpoints = run.checkpoints;
    std::uint32_t done = 0;
    std::uint64_t next = 1;
    const std::uint64_t limit = settings.max_spp ? settings.max_spp : (1ull << 31);
    while (done < limit) {
        std::uint64_t target = std::min(next, limit);
        const double elapsed = integrator.stats().render_seconds - start_seconds;
        if (settings.max_seconds > 0.0 && done > 0) {
            // Cut the batch to what the time left allows at the rate so far.
            const double per_spp = elapsed / done;
            const double fits = std::floor((settings.max_seconds - elapsed) / per_spp);
            if (fits < 1.0)
                break;
            target = std::min<std::uint64_t>(target, done + static_cast<std::uint64_t>(fits));
        }
        integrator.render(settings.first_sample + done, static_cast<std::uint32_t>(target - done),
                          film);
        done = static_cast<std::uint32_t>(target);
        const double seconds = integrator.stats().render_seconds - start_seconds;
        checkpoints.push_back(
            measure_checkpoint(film, done, seconds, reference, settings.first_sample));
        if (on_checkpoint)
            on_checkpoint(checkpoints.back());
        next = std::uint64_t{done} * 2;
        if (settings.max_seconds > 0.0 && seconds >= settings.max_seconds)
            break;
    }
    return run;
}

std::string convergence_csv(const ConvergenceRun& run) {
    std::string text = std::string(kCsvHeader) + "\n";
    for (const Checkpoint& c : run.checkpoints) {
        text += run.estimator + "," + std::to_string(run.width) + "," + std::to_string(run.height) +
                "," + std::to_string(c.spp) + "," + number(c.seconds) + "," +
                number(run.build_seconds) + "," + number(run.warm_up_seconds) + "," +
                (c.against_reference ? "reference" : "halves") + "," + number(c.mse) + "," +
                number(c.rmse) + "," + number(c.rel_mse) + "," + number(c.efficiency) + "," +
                number(c.rel_efficiency) + "," + number(c.mse_halves) + "," +
                number(c.rel_mse_halves) + "\n";
    }
    return text;
}

void write_convergence_csv(const std::filesystem::path& path, const ConvergenceRun& run) {
    const std::string text = convergence_csv(run);
    write_bytes_atomically(path, text.data(), text.size());
}

ConvergenceRun read_convergence_csv(const std::filesystem::path& path) {
    std::istringstream in(read_file_text(path));
    std::string line;
    if (!std::getline(in, line) || line != kCsvHeader)
        throw std::runtime_error("'" + path.string() +
                                 "' is not a convergence CSV (its header differs)");
    ConvergenceRun run;
    for (int line_number = 2; std::getline(in, line); ++line_number) {
        if (line.empty())
            continue;
        std::vector<std::string> fields;
        std::stringstream stream(line);
        for (std::string field; std::getline(stream, field, ',');)
            fields.push_back(field);
        try {
            if (fields.size() != 15)
                throw std::invalid_argument("expected 15 fields, found " +
                                            std::to_string(fields.size()));
            run.estimator = fields[0];
            run.width = std::stoi(fields[1]);
            run.height = std::stoi(fields[2]);
            run.build_seconds = parse_number(fields[5]);
            run.warm_up_seconds = parse_number(fields[6]);
            Checkpoint c;
            c.spp = static_cast<std::uint32_t>(std::stoul(fields[3]));
            c.seconds = parse_number(fields[4]);
            if (fields[7] != "reference" && fields[7] != "halves")
                throw std::invalid_argument("error_source must be reference or halves");
            c.against_reference = fields[7] == "reference";
            c.mse = parse_number(fields[8]);
            c.rmse = parse_number(fields[9]);
            c.rel_mse = parse_number(fields[10]);
            c.efficiency = parse_number(fields[11]);
            c.rel_efficiency = parse_number(fields[12]);
            c.mse_halves = parse_number(fields[13]);
            c.rel_mse_halves = parse_number(fields[14]);
            run.checkpoints.push_back(c);
        } catch (const std::exception& e) {
            throw std::runtime_error("'" + path.string() + "' line " + std::to_string(line_number) +
                                     ": " + e.what());
        }
    }
    return run;
}

LogLogPlot convergence_plot(const std::vector<ConvergenceRun>& runs, const std::string& title) {
    LogLogPlot plot;
    plot.title = title;
    plot.x_label = "render time in seconds (kernel build excluded)";
    const bool reference =
        !runs.empty() && !runs[0].checkpoints.empty() && runs[0].checkpoints[0].against_reference;
    plot.y_label =
        reference ? "RMSE against the reference" : "RMSE (estimated from the even/odd half images)";
    double x_min = HUGE_VAL, x_max = 0.0;
    for (std::size_t r = 0; r < runs.size(); ++r) {
        PlotSeries series;
        series.label = runs[r].estimator;
        for (const Checkpoint& c : runs[r].checkpoints) {
            series.x.push_back(c.seconds);
            series.y.push_back(c.rmse);
            if (r == 0)
                series.point_labels.push_back(std::to_string(c.spp) + " spp");
            if (std::isfinite(c.rmse) && c.seconds > 0.0) {
                x_min = std::min(x_min, c.seconds);
                x_max = std::max(x_max, c.seconds);
            }
        }
        plot.series.push_back(std::move(series));
    }
    // The ideal rate through the first run's last measured point.
    if (!runs.empty()) {
        for (auto it = runs[0].checkpoints.rbegin(); it != runs[0].checkpoints.rend(); ++it) {
            if (std::isfinite(it->rmse) && it->rmse > 0.0 && it->seconds > 0.0) {
                plot.series.push_back(slope_line(-0.5, it->seconds, it->rmse, x_min, x_max,
                                                 "ideal: RMSE ~ time^-1/2"));
                break;
            }
        }
    }
    return plot;
}

double log_log_slope(const std::vector<double>& x, const std::vector<double>& y, double x_min,
                     double x_max) {
    double n = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (std::size_t i = 0; i < std::min(x.size(), y.size()); ++i) {
        if (!(x[i] > 0.0 && y[i] > 0.0 && std::isfinite(x[i]) && std::isfinite(y[i])) ||
            x[i] < x_min || x[i] > x_max)
            continue;
        const double lx = std::log(x[i]), ly = std::log(y[i]);
        n += 1;
        sx += lx;
        sy += ly;
        sxx += lx * lx;
        sxy += lx * ly;
    }
    const double denominator = n * sxx - sx * sx;
    if (n < 2 || denominator <= 0.0)
        return kNaN;
    return (n * sxy - sx * sy) / denominator;
}

double time_to_rel_mse(const std::vector<Checkpoint>& checkpoints, double target) {
    const Checkpoint* previous = nullptr;
    for (const Checkpoint& c : checkpoints) {
        if (!std::isfinite(c.rel_mse))
            continue;
        if (c.rel_mse <= target) {
            if (previous == nullptr || !(previous->seconds > 0.0) || !(c.seconds > 0.0))
                return c.seconds;
            // log-log interpolation between the two checkpoints around the target
            const double a = std::log(previous->rel_mse), b = std::log(c.rel_mse);
            const double f = (std::log(target) - a) / (b - a);
            return std::exp(std::log(previous->seconds) +
                            f * (std::log(c.seconds) - std::log(previous->seconds)));
        }
        previous = &c;
    }
    return kNaN;
}

} // namespace wp
