#include "mcws/report/report_page.h"

#include <cctype>
#include <cstdlib>
#include <map>
#include <string>

#include "mcws/core/error.h"
#include "mcws/core/markup.h"
#include "mcws/core/text_file.h"
#include "mcws/report/detail/page_sources.h"
#include "mcws/report/detail/scene_data.h"

namespace mcws::report {
namespace {

using nlohmann::json;

/// JSON for a <script type="application/json">: every '<' written \u003c, so that no "</script"
/// or "<!--" ends or confuses the element; JSON.parse reads the same value back.
std::string scriptJson(const json& value) {
  const std::string text = value.dump(-1, ' ', false, json::error_handler_t::replace);
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    if (c == '<')
      out += "\\u003c";
    else
      out += c;
  }
  return out;
}

/// Script text inside <script>: "</script" (in a string or comment of a library) written
/// "<\/script", which JavaScript reads the same in strings, regular expressions and comments.
std::string scriptText(const std::string& code) {
  std::string out;
  out.reserve(code.size());
  for (std::size_t i = 0; i < code.size(); ++i) {
    if (code.compare(i, 2, "</") == 0 && i + 8 <= code.size()) {
      std::string tag = code.substr(i + 2, 6);
      for (char& c : tag) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
      if (tag == "script") {
        out += "<\\/";
        ++i;
        continue;
      }
    }
    out += code[i];
  }
  return out;
}

std::string readThreeJs(const std::string& relative) {
  const std::string path = threeJsDirectory() + "/" + relative;
  try {
    return readTextFile(path, "three.js file");
  } catch (const Error& e) {
    throw Error(std::string(e.what()) +
                " (Debian: apt-get install libjs-three, or set MCWS_THREE_JS_DIR)");
  }
}

/// The value at `pointer` (a member `field` of answer `index`), which must be in the report and,
/// when the answer also states it as `stated`, equal to it.
void checkPointer(const json& report, const json& answer, std::size_t index,
                  const std::string& field, const std::string& stated) {
  if (!answer.contains(field)) return;
  const std::string what = "report view: answer " + std::to_string(index) + " (\"" +
                           answer.value("label", std::string()) + "\"): " + field + " ";
  if (!answer[field].is_string()) throw Error(what + "is not a string: " + answer[field].dump());
  const std::string text = answer[field].get<std::string>();
  json::json_pointer pointer;
  try {
    pointer = json::json_pointer(text);
  } catch (const json::exception&) {
    throw Error(what + "\"" + text + "\" is not a JSON pointer");
  }
  if (!report.contains(pointer)) throw Error(what + text + " is not in the report");
  if (answer.contains(stated) && report.at(pointer) != answer[stated])
    throw Error(what + text + " holds " + report.at(pointer).dump() + ", the answer states " +
                stated + " " + answer[stated].dump());
}

/// A section's members that the page reads as arrays are arrays (a table's rows of cells, a
/// chart's series with x and y of one length, a timeline's lanes and events).
void checkSection(const json& section, std::size_t index) {
  const std::string what = "report view: section " + std::to_string(index) + ": ";
  const std::string kind = section.is_object() ? section.value("kind", "") : "";
  auto requireArray = [&](const json& parent, const char* key, const std::string& name) {
    if (!parent.contains(key) || !parent[key].is_array())
      throw Error(what + name + " is not an array: " +
                  (parent.contains(key) ? parent[key].dump() : std::string("missing")));
  };
  if (kind == "table") {
    requireArray(section, "columns", "columns");
    requireArray(section, "rows", "rows");
    for (std::size_t r = 0; r < section["rows"].size(); ++r)
      if (!section["rows"][r].is_array())
        throw Error(what + "row " + std::to_string(r) +
                    " is not an array: " + section["rows"][r].dump());
  } else if (kind == "chart") {
    requireArray(section, "series", "series");
    for (std::size_t s = 0; s < section["series"].size(); ++s) {
      const json& series = section["series"][s];
      const std::string name = "series " + std::to_string(s);
      requireArray(series, "x", name + " x");
      requireArray(series, "y", name + " y");
      if (series["x"].size() != series["y"].size())
        throw Error(what + name + ": " + std::to_string(series["x"].size()) + " x values, " +
                    std::to_string(series["y"].size()) + " y values");
    }
  } else if (kind == "timeline") {
    requireArray(section, "lanes", "lanes");
    requireArray(section, "events", "events");
  } else if (kind != "image" && kind != "text") {
    throw Error(what + "kind \"" + kind + "\" is none of table, image, chart, timeline, text");
  }
}

/// The view's answers point into the report at the numbers they show; its sections are of the
/// kinds the page draws.
void checkView(const json& report) {
  if (!report.is_object())
    throw Error(std::string("report: a JSON object expected, not ") + report.type_name());
  if (!report.contains("view")) return;
  const json& view = report["view"];
  if (!view.is_object())
    throw Error(std::string("report view: not an object but ") + view.type_name());
  const json answers = view.value("answers", json::array());
  for (std::size_t i = 0; i < answers.size(); ++i) {
    if (!answers[i].is_object())
      throw Error("report view: answer " + std::to_string(i) + " is not an object");
    checkPointer(report, answers[i], i, "source", "value");
    checkPointer(report, answers[i], i, "interval_source", "interval");
  }
  const json sections = view.value("sections", json::array());
  for (std::size_t i = 0; i < sections.size(); ++i) checkSection(sections[i], i);
}

/// The template with every <!--mcws:NAME--> replaced by parts[NAME] (inserted text is not
/// searched again).
std::string fill(const std::string& page, const std::map<std::string, std::string>& parts) {
  static const std::string kOpen = "<!--mcws:", kClose = "-->";
  std::string out;
  std::size_t at = 0;
  for (std::size_t open; (open = page.find(kOpen, at)) != std::string::npos;) {
    const std::size_t close = page.find(kClose, open);
    const std::string name = page.substr(open + kOpen.size(), close - open - kOpen.size());
    out.append(page, at, open - at);
    out += parts.at(name);
    at = close + kClose.size();
  }
  out.append(page, at, std::string::npos);
  return out;
}

}  // namespace

std::string threeJsDirectory() {
  const char* directory = std::getenv("MCWS_THREE_JS_DIR");
  return directory != nullptr && *directory != '\0' ? directory : "/usr/share/javascript/three";
}

std::string reportHtml(const nlohmann::json& report, const Scene& scene,
                       const PageOptions& options) {
  try {
    checkView(report);
  } catch (const json::exception& e) {  // a member of another type than the page reads
    throw Error(std::string("report view: ") + e.what());
  }
  detail::checkScene(scene);
  const detail::Decimation cut = detail::decimation(scene, options.max_embedded_bytes);
  const std::string three = readThreeJs("build/three.min.js");
  const std::string orbit = readThreeJs("examples/js/controls/OrbitControls.js");
  return fill(detail::kPageReportHtml, {{"title", escapeMarkup(options.title)},
                                        {"css", detail::kPageReportCss},
                                        {"report", scriptJson(report)},
                                        {"scene", scriptJson(detail::sceneJson(scene, cut))},
                                        {"three", scriptText(three)},
                                        {"orbit", scriptText(orbit)},
                                        {"js", std::string(detail::kPageSectionsJs) +
                                                   detail::kPageView3dJs + detail::kPageReportJs}});
}

}  // namespace mcws::report
