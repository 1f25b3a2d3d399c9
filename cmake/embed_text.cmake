# cmake -DOUTPUT=file.cpp -DINPUTS="a.txt|b.txt" -DNAMESPACE=ns -DFUNCTION=Name [-DKEY=name] -P embed_text.cmake
# Writes a C++ file defining ns::Name(): each file's key and its text, in the order given. The
# key is the file's stem ("a"), or with -DKEY=name its whole name ("a.txt"). Text files only,
# holding anything but the raw string's delimiter.
set(body "")
string(REPLACE "|" ";" INPUTS "${INPUTS}")
foreach(file IN LISTS INPUTS)
  file(READ ${file} text)
  if(KEY STREQUAL "name")
    get_filename_component(key ${file} NAME)
  else()
    get_filename_component(key ${file} NAME_WE)
  endif()
  string(FIND "${text}" ")embedded\"" clash)
  if(NOT clash EQUAL -1)
    message(FATAL_ERROR "${file} contains the raw string delimiter )embedded\"")
  endif()
  string(APPEND body "      {\"${key}\", R\"embedded(${text})embedded\"},\n")
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
