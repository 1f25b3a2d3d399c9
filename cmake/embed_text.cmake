# cmake -DOUTPUT=file.cpp -DINPUTS="a.txt|b.txt" -DNAMESPACE=ns -DFUNCTION=Name -P embed_text.cmake
# Writes a C++ file defining ns::Name(): the files' stems and texts, in the order given.
set(body "")
string(REPLACE "|" ";" INPUTS "${INPUTS}")
foreach(file IN LISTS INPUTS)
  file(READ ${file} text)
  get_filename_component(stem ${file} NAME_WE)
  string(APPEND body "      {\"${stem}\", R\"embedded(${text})embedded\"},\n")
endforeach()
file(WRITE ${OUTPUT} "// Generated at build time by cmake/embed_text.cmake; do not edit.
#include <string_view>
#include <utility>
#include <vector>

namespace ${NAMESPACE} {
const std::vector<std::pair<std::string_view, std::string_view>>& ${FUNCTION}() {
  static const std::vector<std::pair<std::string_view, std::string_view>> files = {
${body}  };
  return files;
}
}  // namespace ${NAMESPACE}
")
