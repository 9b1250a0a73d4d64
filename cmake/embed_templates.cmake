# Writes OUTPUT, a C++ source defining pfgen::codegen::embedded_template(), with
# the text of every template compiled in as a raw string: the files under TEMPLATE_DIR; with
# BACKEND_ROOT (optional) those under each <BACKEND_ROOT>/<language>/templates, a backend's own,
# each named <language>/<its path below templates> ("cpp/filter.hpp.tmpl"); and with MODULE_ROOT
# (optional) those under each <MODULE_ROOT>/<module>/templates, each named by its path below its
# templates folder. One name space for all. Run at build time, so editing a template rebuilds pfgen.
set(template_roots "${TEMPLATE_DIR}")
set(root_prefixes "")
list(APPEND root_prefixes "-")
if(BACKEND_ROOT)
  file(GLOB backend_folders LIST_DIRECTORIES true "${BACKEND_ROOT}/*/templates")
  list(SORT backend_folders)
  foreach(folder IN LISTS backend_folders)
    get_filename_component(language_folder "${folder}" DIRECTORY)
    get_filename_component(language "${language_folder}" NAME)
    list(APPEND template_roots "${folder}")
    list(APPEND root_prefixes "${language}/")
  endforeach()
endif()
if(MODULE_ROOT)
  file(GLOB module_template_roots LIST_DIRECTORIES true "${MODULE_ROOT}/*/templates")
  list(SORT module_template_roots)
  foreach(folder IN LISTS module_template_roots)
    list(APPEND template_roots "${folder}")
    list(APPEND root_prefixes "-")
  endforeach()
endif()
set(body "")
set(names "")
list(LENGTH template_roots root_count)
math(EXPR last_root "${root_count} - 1")
foreach(k RANGE ${last_root})
  list(GET template_roots ${k} root)
  list(GET root_prefixes ${k} prefix)
  if(prefix STREQUAL "-")
    set(prefix "")
  endif()
  file(GLOB_RECURSE template_files RELATIVE "${root}" "${root}/*.tmpl")
  list(SORT template_files)
  foreach(relative IN LISTS template_files)
    set(embedded "${prefix}${relative}")
    list(FIND names "${embedded}" seen)
    if(NOT seen EQUAL -1)
      message(FATAL_ERROR "embed_templates: two templates are named ${embedded} (the second in ${root})")
    endif()
    list(APPEND names "${embedded}")
    file(READ "${root}/${relative}" text)
    string(APPEND body "      {\"${embedded}\", R\"pfgen_template(${text})pfgen_template\"},\n")
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
