# Writes OUTPUT, a C++ source defining pfgen::codegen::embedded_template(), with
# the text of every file under TEMPLATE_DIR compiled in as a raw string. Run at
# build time, so editing a template rebuilds pfgen.
file(GLOB_RECURSE template_files RELATIVE "${TEMPLATE_DIR}" "${TEMPLATE_DIR}/*.tmpl")
list(SORT template_files)
set(body "")
foreach(relative IN LISTS template_files)
  file(READ "${TEMPLATE_DIR}/${relative}" text)
  string(APPEND body "      {\"${relative}\", R\"pfgen_template(${text})pfgen_template\"},\n")
endforeach()
# EXTRA_FILES (relative to EXTRA_ROOT, optional): other files pfgen writes out, such as the plugin
# ABI header that the runtime also includes, so that both share one definition.
foreach(relative IN LISTS EXTRA_FILES)
  file(READ "${EXTRA_ROOT}/${relative}" text)
  string(APPEND body "      {\"${relative}\", R\"pfgen_template(${text})pfgen_template\"},\n")
endforeach()
file(WRITE "${OUTPUT}.tmp" "// Generated from templates/ at build time. Do not edit.
#include \"pfgen/codegen/template_text.hpp\"

#include <stdexcept>

namespace pfgen::codegen {

const std::string& embedded_template(const std::string& relative_path) {
  static const std::map<std::string, std::string> templates = {
${body}  };
  auto it = templates.find(relative_path);
  if (it == templates.end()) throw std::logic_error(\"no template \" + relative_path);
  return it->second;
}

}  // namespace pfgen::codegen
")
file(COPY_FILE "${OUTPUT}.tmp" "${OUTPUT}" ONLY_IF_DIFFERENT)
file(REMOVE "${OUTPUT}.tmp")
