// sward-eval in a build without OpenCV (SWARD_WITH_OPENCV=OFF; tools/sward-eval/CMakeLists.txt builds this file
// instead of the commands): --help and --version as always, every evaluation one error naming OpenCV and the option.
#include "common/optional_components.h"

#include "tools/tool_main.h"

#include <CLI/CLI.hpp>

int main(int argc, char** argv) {
    CLI::App app{"sward-eval: evaluations of a sward dataset (left out of this build: SWARD_WITH_OPENCV=OFF)"};
    app.allow_extras(); // whatever the command, the answer is the same error
    return sward::runTool(app, argc, argv, "sward-eval", [] {
        sward::requireComponent(sward::Component::OpenCv, "sward-eval");
        return 0;
    });
}
