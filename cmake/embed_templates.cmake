# Writes OUTPUT, a C++ source defining pfgen::codegen::embedded_template(), with
# the text of every template compiled in as a raw string: the files under TEMPLATE_DIR, and with
# MODULE_ROOT (optional) those under each <MODULE_ROOT>/<module>/templates, the observation
# modules' own, each named by its path below its templates folder ("cpp/filter.hpp.tmpl"), one
# name space for all. Run at build time, so editing a template rebuilds pfgen.
set(template_roots "${TEMPLATE_DIR}")
if(MODULE_ROOT)
  file(GLOB module_template_roots LIST_DIRECTORIES true "${MODULE_ROOT}/*/templates")
  list(SORT module_template_roots)
  list(APPEND template_roots ${module_template_roots})
endif()
set(body "")
set(names "")
foreach(root IN LISTS template_roots)
  file(GLOB_RECURSE template_files RELATIVE "${root}" "${root}/*.tmpl")
  list(SORT template_files)
  foreach(relative IN LISTS template_files)
    list(FIND names "${relative}" seen)
    if(NOT seen EQUAL -1)
      message(FATAL_ERROR "embed_templates: two templates are named ${relative} (the second in ${root})")
    endif()
    list(APPEND names "${relative}")
    file(READ "${root}/${relative}" text)
    string(APPEND body "      {\"${relative}\", R\"pfgen_template(${text})pfgen_template\"},\n")
  endforeach()
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
