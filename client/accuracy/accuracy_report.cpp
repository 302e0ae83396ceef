#include "client/accuracy/accuracy_report.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>

#include "common/base/error.h"

namespace glint {
namespace {

// The error scale of the false-colour images: (error, colour) stops.
constexpr std::array<std::pair<float, std::array<float, 3>>, 5> kRamp{{{0.0f, {0, 0, 0}},
                                                                        {1.0f / 255, {0, 0, 255}},
                                                                        {4.0f / 255, {0, 200, 0}},
                                                                        {8.0f / 255, {255, 230, 0}},
                                                                        {32.0f / 255, {255, 0, 0}}}};

std::array<std::uint8_t, 3> rampColour(float e) {
  if (e >= kRamp.back().first) return {255, 0, 0};
  for (std::size_t i = 1; i < kRamp.size(); ++i) {
    if (e > kRamp[i].first) continue;
    const float t = (e - kRamp[i - 1].first) / (kRamp[i].first - kRamp[i - 1].first);
    std::array<std::uint8_t, 3> c{};
    for (int k = 0; k < 3; ++k) {
      c[k] = static_cast<std::uint8_t>(std::lround(kRamp[i - 1].second[k] + t * (kRamp[i].second[k] - kRamp[i - 1].second[k])));
    }
    return c;
  }
  return {0, 0, 0};
}

std::ofstream create(const std::filesystem::path& path) {
  std::ofstream out(path, std::ios::trunc);
  if (!out) throw InputError(path.string() + ": cannot write (check that the folder is writable)");
  return out;
}

// Series in the order they first appear.
std::vector<std::string> seriesNames(const std::vector<AccuracyRow>& rows) {
  std::vector<std::string> names;
  for (const AccuracyRow& r : rows) {
    if (std::find(names.begin(), names.end(), r.name) == names.end()) names.push_back(r.name);
  }
  return names;
}

// Errors as plotted: a log axis cannot show 0 (a row equal to the reference).
double onLogAxis(double rmse) { return std::max(rmse, 1e-6); }

std::string fixed(double v, int digits) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", digits, v);
  return text;
}

}  // namespace

FrameImage errorImage(const std::vector<float>& perPixel, int width, int height) {
  FrameImage image{width, height, std::vector<std::uint8_t>(perPixel.size() * 3)};
  for (std::size_t p = 0; p < perPixel.size(); ++p) {
    const auto c = rampColour(perPixel[p]);
    std::copy(c.begin(), c.end(), image.rgb.begin() + static_cast<std::ptrdiff_t>(3 * p));
  }
  return image;
}

double errorOf(const AccuracyRow& row, AccuracyMetric metric) {
  return metric == AccuracyMetric::kFlip ? row.flip.mean : row.error.rmse;
}

std::vector<bool> paretoFront(const std::vector<AccuracyRow>& rows, AccuracyMetric metric) {
  std::vector<bool> front(rows.size(), true);
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const double ei = errorOf(rows[i], metric);
    for (std::size_t j = 0; j < rows.size() && front[i]; ++j) {
      const double ej = errorOf(rows[j], metric);
      const bool noWorse = rows[j].timeMs <= rows[i].timeMs && ej <= ei;
      const bool better = rows[j].timeMs < rows[i].timeMs || ej < ei;
      if (j != i && noWorse && better) front[i] = false;
    }
  }
  return front;
}

void writeCsv(const std::filesystem::path& dir, const std::vector<AccuracyRow>& rows) {
  std::ofstream out = create(dir / "accuracy.csv");
  out << "name,value,scene_setting,time_ms,rays,primary,shadow,reflection,refraction,rmse,psnr_db,max_error,"
         "over_1_255,over_8_255,flip,flip_p95,flip_p99,image\n";
  for (const AccuracyRow& r : rows) {
    out << r.name << ',' << r.value << ',' << (r.sceneSetting ? 1 : 0) << ',' << fixed(r.timeMs, 2) << ','
        << r.rays.total() << ',' << r.rays.primary << ',' << r.rays.shadow << ',' << r.rays.reflection << ','
        << r.rays.refraction << ',' << r.error.rmse << ',' << fixed(r.error.psnrDb, 2) << ',' << r.error.maxError
        << ',' << r.error.over1 << ',' << r.error.over8 << ',' << fixed(r.flip.mean, 6) << ','
        << fixed(r.flip.p95, 6) << ',' << fixed(r.flip.p99, 6) << ',' << r.image << '\n';
  }
}

// accuracy.dat holds one block per series (gnuplot's `index`), pareto.dat
// the front, scene.dat the scene's own settings; accuracy.gp plots them.
bool writePlot(const std::filesystem::path& dir, const std::vector<AccuracyRow>& rows,
               const AccuracyReference& reference, AccuracyMetric metric) {
  const std::vector<std::string> names = seriesNames(rows);
  const std::vector<bool> front = paretoFront(rows, metric);
  {
    std::ofstream data = create(dir / "accuracy.dat"), pareto = create(dir / "pareto.dat"),
                  scene = create(dir / "scene.dat");
    for (const std::string& name : names) {
      data << "# " << name << '\n';
      for (const AccuracyRow& r : rows) {
        if (r.name == name) data << r.timeMs << ' ' << onLogAxis(errorOf(r, metric)) << ' ' << r.value << '\n';
      }
      data << "\n\n";
    }
    std::vector<std::pair<double, double>> points;
    for (std::size_t i = 0; i < rows.size(); ++i) {
      if (front[i]) points.emplace_back(rows[i].timeMs, onLogAxis(errorOf(rows[i], metric)));
      if (rows[i].sceneSetting) scene << rows[i].timeMs << ' ' << onLogAxis(errorOf(rows[i], metric)) << '\n';
    }
    std::sort(points.begin(), points.end());
    for (const auto& [t, e] : points) pareto << t << ' ' << e << '\n';
  }
  std::string titles;
  for (const std::string& n : names) titles += (titles.empty() ? "" : " ") + n;
  const bool flip = metric == AccuracyMetric::kFlip;
  const double referenceLine = onLogAxis(flip ? reference.halvesFlip : reference.ownRmse);
  std::ofstream script = create(dir / "accuracy.gp");
  script << "set terminal pngcairo size 1000,680 font 'sans,11' noenhanced\nset output 'accuracy.png'\n"
         << "set logscale xy\nset grid\nset key outside right\n"
         << "set yrange [" << referenceLine * 0.5 << ":*]\n"
         << "set arrow from graph 0, first " << referenceLine << " to graph 1, first "
         << referenceLine << " nohead dt 3 lc rgb 'gray40'\n"
         << "set label \"" << (flip ? "the reference's two halves against each other" : "the reference's own error")
         << "\" at graph 0.02, first " << referenceLine * 1.15 << " tc rgb 'gray40'\n"
         << "set xlabel 'frame time (ms, median)'\nset ylabel '"
         << (flip ? "mean FLIP against the reference (0-1)" : "RMSE against the reference (linear, 0-1)") << "'\n"
         << "set title 'What accuracy costs in time'\nnames = '" << titles << "'\n"
         << "plot for [i=1:words(names)] 'accuracy.dat' index (i-1) using 1:2 with linespoints lw 2 pt 7 "
            "title word(names, i), \\\n"
         << "     'pareto.dat' using 1:2 with lines dt 2 lw 1 lc rgb 'black' title 'Pareto front'";
  // scene.dat only where a row is the scene's own setting (gnuplot warns of an empty file).
  const bool sceneRows = std::any_of(rows.begin(), rows.end(), [](const AccuracyRow& r) { return r.sceneSetting; });
  if (sceneRows) {
    script << ", \\\n     'scene.dat' using 1:2 with points pt 6 ps 2.5 lc rgb 'black' title \"the scene's setting\"";
  }
  script << "\n";
  script.close();
  if (std::system("command -v gnuplot > /dev/null 2>&1") != 0) return false;
  const std::string command = "cd '" + dir.string() + "' && gnuplot accuracy.gp";
  return std::system(command.c_str()) == 0;
}

namespace {

void writeTable(std::ofstream& out, const std::vector<AccuracyRow>& rows, const std::vector<bool>& front) {
  out << "| setting | value | time ms | rays | FLIP | FLIP p95 | FLIP p99 | RMSE | PSNR dB | max error | "
         "pixels > 8/255 | Pareto |\n|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const AccuracyRow& r = rows[i];
    out << "| " << r.name << " | " << r.value << (r.sceneSetting ? " (scene)" : "") << " | " << fixed(r.timeMs, 1)
        << " | " << r.rays.total() << " | " << fixed(r.flip.mean, 4) << " | " << fixed(r.flip.p95, 3) << " | "
        << fixed(r.flip.p99, 3) << " | " << fixed(r.error.rmse, 5) << " | " << fixed(r.error.psnrDb, 1) << " | "
        << fixed(r.error.maxError, 3) << " | " << fixed(100.0 * r.error.over8, 1) << " % | "
        << (front[i] ? "yes" : "") << " |\n";
  }
}

// Two sentences from the numbers: the cheapest good-enough row and how many
// rows the front needs.
void writeSummary(std::ofstream& out, const std::vector<AccuracyRow>& rows, const std::vector<bool>& front,
                  AccuracyMetric metric) {
  const std::string word = metric == AccuracyMetric::kFlip ? "FLIP" : "RMSE";
  const auto best = std::min_element(rows.begin(), rows.end(), [metric](const AccuracyRow& a, const AccuracyRow& b) {
    return errorOf(a, metric) < errorOf(b, metric);
  });
  const AccuracyRow* cheapest = nullptr;
  for (const AccuracyRow& r : rows) {
    if (errorOf(r, metric) <= 1.25 * errorOf(*best, metric) && (!cheapest || r.timeMs < cheapest->timeMs)) {
      cheapest = &r;
    }
  }
  out << "\nBy " << word << ", the most accurate row is " << best->name << " = " << best->value << " (" << word
      << " " << fixed(errorOf(*best, metric), 5) << ", " << fixed(best->timeMs, 1)
      << " ms); within 25 % of its error, the cheapest is " << cheapest->name << " = " << cheapest->value << " at "
      << fixed(cheapest->timeMs, 1) << " ms. ";
  std::size_t onFront = 0;
  for (const bool f : front) onFront += f ? 1 : 0;
  out << onFront << " of " << rows.size()
      << " settings are on the Pareto front; every other one is beaten in both time and error by one of them.\n";
}

// The rows drawn from an irradiance field: how much of their time filled it.
void writeFieldFills(std::ostream& out, const std::vector<AccuracyRow>& rows) {
  std::string fills;
  for (const AccuracyRow& row : rows) {
    if (row.fieldMs <= 0.0) continue;
    fills += (fills.empty() ? "" : ", ") + row.name + " = " + row.value + ": " + fixed(row.fieldMs, 1) + " of " +
             fixed(row.timeMs, 1) + " ms";
  }
  if (fills.empty()) return;
  out << "\nA row drawn from an irradiance field counts the field's fill in its time, as a first frame does; a "
         "later frame of the same scene and settings reuses the field and skips it ("
      << fills << ").\n";
}

}  // namespace

double ownError(const AccuracyReference& reference, AccuracyMetric metric) {
  return metric == AccuracyMetric::kFlip ? reference.halvesFlip / 2.0 : reference.ownRmse;
}

bool nearTheReferencesNoise(const AccuracyRow& row, const AccuracyReference& reference, AccuracyMetric metric) {
  return errorOf(row, metric) < 2.0 * ownError(reference, metric);
}

namespace {

// The rows whose error is within 2x of the reference's own.
void writeNoisyRows(std::ostream& out, const std::vector<AccuracyRow>& rows, const AccuracyReference& reference,
                    AccuracyMetric metric) {
  std::string noisy;
  for (const AccuracyRow& row : rows) {
    if (nearTheReferencesNoise(row, reference, metric)) noisy += (noisy.empty() ? "" : ", ") + row.name + " = " + row.value;
  }
  if (noisy.empty()) return;
  out << "\nWithin 2x of the reference's own error, so that much of what they measure may be the reference's "
         "noise (more --reference-samples would tell them apart): "
      << noisy << ".\n";
}

}  // namespace

void writeReport(const std::filesystem::path& dir, const std::string& scene, const AccuracyReference& reference,
                 const std::vector<AccuracyRow>& rows, AccuracyMetric metric, bool plotted) {
  std::ofstream out = create(dir / "report.md");
  const std::vector<bool> front = paretoFront(rows, metric);
  out << "# What accuracy costs in time: " << scene << "\n\n";
  out << "Reference: " << reference.samples << " " << reference.pattern << " samples per pixel, " << reference.light
      << " (" << fixed(reference.timeMs / 1000.0, 1) << " s). Its own error, estimated from two "
      << "half-sample references against each other, is RMSE " << reference.ownRmse << " and FLIP about "
      << fixed(ownError(reference, AccuracyMetric::kFlip), 4)
      << ": differences below it mean nothing. The two halves differ by a mean FLIP of "
      << fixed(reference.halvesFlip, 4) << ".\n\n";
  if (plotted) out << "![error against time](accuracy.png)\n\n";
  writeTable(out, rows, front);
  writeNoisyRows(out, rows, reference, metric);
  if (!rows.empty()) writeSummary(out, rows, front, metric);
  writeFieldFills(out, rows);
}

}  // namespace glint
