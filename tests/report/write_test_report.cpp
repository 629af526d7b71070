// Writes the synthetic report page (tests/report/synthetic_report.h) that the browser test opens.
// Usage: write_test_report OUT.html [BOUNDARY_POINTS [MAX_EMBEDDED_BYTES]]

#include <cstdlib>
#include <fstream>
#include <iostream>

#include "mcws/core/error.h"
#include "report/synthetic_report.h"

int main(int argc, char** argv) {
  if (argc < 2 || argc > 4) {
    std::cerr << "usage: write_test_report OUT.html [BOUNDARY_POINTS [MAX_EMBEDDED_BYTES]]\n";
    return 2;
  }
  try {
    mcws::report::PageOptions options;
    options.title = "mcws synthetic report";
    std::size_t points = 2000;
    if (argc > 2) points = std::stoul(argv[2]);
    if (argc > 3) options.max_embedded_bytes = std::stoul(argv[3]);
    const std::string page = mcws::report::reportHtml(mcws::test::syntheticReport(),
                                                      mcws::test::syntheticScene(points), options);
    std::ofstream out(argv[1], std::ios::binary);
    out << page;
    if (!out.flush()) throw mcws::Error(std::string(argv[1]) + ": cannot write the page");
  } catch (const std::exception& e) {
    std::cerr << "write_test_report: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
