# cmake -DOUTPUT=file.cpp -DINPUTS="dir/a.js|dir/b.css" -DNAMESPACE=ns -DFUNCTION=Name -P embed_files.cmake
# Writes a C++ file defining ns::Name(): each file's name (without directories) and its text,
# in the order given. For text files that may hold anything but the raw string's delimiter.
set(body "")
string(REPLACE "|" ";" INPUTS "${INPUTS}")
foreach(file IN LISTS INPUTS)
  file(READ ${file} text)
  get_filename_component(name ${file} NAME)
  string(FIND "${text}" ")flagsimfile\"" clash)
  if(NOT clash EQUAL -1)
    message(FATAL_ERROR "${file} contains the raw string delimiter )flagsimfile\"")
  endif()
  string(APPEND body "      {\"${name}\", R\"flagsimfile(${text})flagsimfile\"},\n")
endforeach()
file(WRITE ${OUTPUT} "// Generated at build time by cmake/embed_files.cmake; do not edit.
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
