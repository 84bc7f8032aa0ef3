#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""JSON and field-unit code for every IDL type, generated from the IDL.

Topics are defined once, in idl/*.idl; fastddsgen generates the C++ types and
this script generates, next to them, for every struct X and enum E:

    nlohmann::ordered_json toJson(const X&);   // fields in IDL order
    nlohmann::ordered_json toJson(E);          // the enumerator's name
    std::string_view toString(E);
    fieldUnits<X>()   // direct fields: name, unit, meaning (from `// [unit] meaning`)
    leafFields<X>()   // the leaves of toJson(X), flattened: "header.step", "b_body_T[0]"
    leafValue<X>(x, i), setLeaf<X>(x, i, v)   // numeric leaf i of leafFields<X>() as a double
    idlName<X>()      // "flatsat::msg::TruthState"

char arrays become strings (up to the first NUL), other fixed arrays JSON
arrays, nested structs objects.

The IDL subset: modules, structs, enums, integer constants, typedefs of
the below, members of primitive types, `string`, fixed (multi-dimensional)
arrays and nested structs/enums, `#include`/`#pragma` lines (the files are
given together), annotations (ignored). Anything else is an error naming
file:line.

usage: gen_json.py -o OUT_DIR [--name MsgJson] [--include-prefix msg] A.idl B.idl ...
"""
import argparse
import os
import re
import sys

# IDL primitive type spellings; fastddsgen maps them to C++ arithmetic types
# (string to std::string), which nlohmann::json takes as they are.
PRIMITIVES = frozenset({
    "boolean", "char", "wchar", "octet", "int8", "uint8", "short", "int16",
    "unsigned short", "uint16", "long", "int32", "unsigned long", "uint32",
    "long long", "int64", "unsigned long long", "uint64", "float", "double",
    "long double", "string",
})

UNIT_COMMENT = re.compile(r"^\s*\[([^\]]*)\]\s*(.*)$")
TOKEN = re.compile(
    r"""(?P<ws>[ \t\r]+)
      | (?P<nl>\n)
      | (?P<comment>//[^\n]*)
      | (?P<block>/\*.*?\*/)
      | (?P<directive>\#[^\n]*)
      | (?P<string>"(?:[^"\\\n]|\\.)*")
      | (?P<name>[A-Za-z_][A-Za-z0-9_]*(?:::[A-Za-z_][A-Za-z0-9_]*)*|::[A-Za-z_][A-Za-z0-9_:]*)
      | (?P<number>0[xX][0-9a-fA-F]+|\d+)
      | (?P<punct>[{}\[\];,<>()=:@\-+*/])
    """,
    re.VERBOSE | re.DOTALL,
)


class IdlError(Exception):
    pass


class Token:
    __slots__ = ("kind", "text", "file", "line")

    def __init__(self, kind, text, file, line):
        self.kind, self.text, self.file, self.line = kind, text, file, line

    def where(self):
        return f"{self.file}:{self.line}"


def tokenize(path, text):
    tokens, line, pos = [], 1, 0
    while pos < len(text):
        m = TOKEN.match(text, pos)
        if not m:
            raise IdlError(f"{path}:{line}: unexpected character {text[pos]!r}")
        kind = m.lastgroup
        value = m.group(kind)
        if kind in ("comment", "name", "number", "punct", "string", "directive"):
            tokens.append(Token(kind, value, path, line))
        line += value.count("\n")
        pos = m.end()
    return tokens


class Field:
    def __init__(self, name, type_name, dims, unit, description, where):
        self.name, self.type_name, self.dims = name, type_name, dims
        self.unit, self.description, self.where = unit, description, where


class Struct:
    def __init__(self, scope, name, where):
        self.scope, self.name, self.where, self.fields = scope, name, where, []

    @property
    def cpp(self):
        return "::".join(self.scope + [self.name])


class Enum:
    def __init__(self, scope, name, where):
        self.scope, self.name, self.where, self.values = scope, name, where, []

    @property
    def cpp(self):
        return "::".join(self.scope + [self.name])


class Parser:
    """Recursive descent over the token list of every file, in order."""

    def __init__(self):
        self.types = {}  # fully scoped name -> Struct | Enum | ("alias", type, dims)
        self.order = []  # Structs and Enums in definition order
        self.constants = {}

    # -- token helpers ------------------------------------------------------
    def parse_file(self, path, parsed):
        """Parses the files a file #includes (next to it), then the file."""
        path = os.path.abspath(path)
        if path in parsed:
            return
        parsed.append(path)
        with open(path, encoding="utf-8") as f:
            tokens = tokenize(path, f.read())
        for tok in tokens:
            m = re.match(r'#\s*include\s*[<"]([^>"]+)[>"]', tok.text) if tok.kind == "directive" else None
            if m:
                self.parse_file(os.path.join(os.path.dirname(path), m.group(1)), parsed)
        self.tokens = [t for t in tokens if t.kind != "directive"]
        self.i = 0
        self.parse([])
        if self.peek() is not None:
            raise IdlError(f"{self.peek().where()}: unexpected '{self.peek().text}'")

    def peek(self):
        j = self.i
        while j < len(self.tokens) and self.tokens[j].kind == "comment":
            j += 1
        return self.tokens[j] if j < len(self.tokens) else None

    def next(self):
        while self.i < len(self.tokens) and self.tokens[self.i].kind == "comment":
            self.i += 1
        if self.i >= len(self.tokens):
            last = self.tokens[-1] if self.tokens else None
            raise IdlError(f"{last.where() if last else '?'}: unexpected end of file")
        tok = self.tokens[self.i]
        self.i += 1
        return tok

    def expect(self, text):
        tok = self.next()
        if tok.text != text:
            raise IdlError(f"{tok.where()}: expected '{text}', found '{tok.text}'")
        return tok

    def name(self):
        tok = self.next()
        if tok.kind != "name":
            raise IdlError(f"{tok.where()}: expected a name, found '{tok.text}'")
        return tok

    def trailing_comment(self, line):
        """The `//` comment right after the last token, on its line."""
        if self.i < len(self.tokens):
            tok = self.tokens[self.i]
            if tok.kind == "comment" and tok.line == line:
                self.i += 1
                return tok.text[2:].strip()
        return ""

    def skip_annotations(self):
        while self.peek() is not None and self.peek().text == "@":
            self.next()
            self.name()
            if self.peek() is not None and self.peek().text == "(":
                depth = 0
                while True:
                    tok = self.next()
                    depth += tok.text == "("
                    depth -= tok.text == ")"
                    if depth == 0:
                        break

    # -- grammar ------------------------------------------------------------
    def parse(self, scope):
        while True:
            self.skip_annotations()
            tok = self.peek()
            if tok is None or tok.text == "}":
                return
            self.definition(scope)

    def definition(self, scope):
        tok = self.next()
        if tok.text == ";":
            return
        if tok.text == "module":
            name = self.name().text
            self.expect("{")
            self.parse(scope + [name])
            self.expect("}")
            self.expect(";")
        elif tok.text == "struct":
            self.struct(scope)
        elif tok.text == "enum":
            self.enum(scope)
        elif tok.text == "const":
            self.const(scope)
        elif tok.text == "typedef":
            self.typedef(scope)
        else:
            raise IdlError(f"{tok.where()}: '{tok.text}' is not in the supported IDL subset "
                           "(module, struct, enum, const, typedef)")

    def register(self, scope, name, entity, where):
        full = "::".join(scope + [name])
        if full in self.types:
            raise IdlError(f"{where}: '{full}' is defined twice")
        self.types[full] = entity

    def struct(self, scope):
        name_tok = self.name()
        if self.peek().text == ";":  # forward declaration
            self.next()
            return
        if self.peek().text == ":":
            raise IdlError(f"{name_tok.where()}: struct inheritance is not supported")
        struct = Struct(scope, name_tok.text, name_tok.where())
        self.expect("{")
        while self.peek().text != "}":
            self.skip_annotations()
            struct.fields.extend(self.member(scope))
        self.expect("}")
        end = self.expect(";")
        self.trailing_comment(end.line)
        if not struct.fields:
            raise IdlError(f"{name_tok.where()}: struct {name_tok.text} has no field")
        self.register(scope, struct.name, struct, struct.where)
        self.order.append(struct)

    def enum(self, scope):
        name_tok = self.name()
        enum = Enum(scope, name_tok.text, name_tok.where())
        self.expect("{")
        while True:
            self.skip_annotations()
            value = self.name()
            sep = self.next()
            enum.values.append(value.text)
            if sep.text == "}":
                break
            if sep.text != ",":
                raise IdlError(f"{sep.where()}: expected ',' or '}}' in enum {enum.name}")
            if self.peek().text == "}":
                self.next()
                break
        self.expect(";")
        self.register(scope, enum.name, enum, enum.where)
        self.order.append(enum)

    def const(self, scope):
        self.type_spec(scope)
        name = self.name()
        self.expect("=")
        self.constants["::".join(scope + [name.text])] = self.int_expr(scope)
        self.expect(";")

    def typedef(self, scope):
        type_name = self.type_spec(scope)
        name = self.name()
        dims = self.dims(scope)
        self.expect(";")
        self.register(scope, name.text, ("alias", type_name, dims), name.where())

    def int_expr(self, scope):
        tok = self.next()
        if tok.kind == "number":
            return int(tok.text, 0)
        if tok.kind == "name":
            value = self.lookup(scope, tok.text, self.constants)
            if value is None:
                raise IdlError(f"{tok.where()}: unknown constant '{tok.text}'")
            return self.constants[value]
        raise IdlError(f"{tok.where()}: expected an integer, found '{tok.text}'")

    def dims(self, scope):
        dims = []
        while self.peek().text == "[":
            self.next()
            n = self.int_expr(scope)
            if n <= 0:
                raise IdlError(f"{self.tokens[self.i - 1].where()}: array size must be positive")
            dims.append(n)
            self.expect("]")
        return dims

    def type_spec(self, scope):
        tok = self.next()
        words = [tok.text]
        if tok.text == "unsigned":
            words.append(self.next().text)
            if words[1] == "long" and self.peek().text == "long":
                words.append(self.next().text)
        elif tok.text == "long" and self.peek().text in ("long", "double"):
            words.append(self.next().text)
        elif tok.text in ("sequence", "map", "wstring", "any", "union", "fixed"):
            raise IdlError(f"{tok.where()}: '{tok.text}' is not in the supported IDL subset")
        spelled = " ".join(words)
        if spelled == "string":
            if self.peek().text == "<":  # bounded string: same C++ type
                self.next()
                self.int_expr(scope)
                self.expect(">")
            return spelled
        if spelled in PRIMITIVES:
            return spelled
        if tok.kind != "name" or len(words) > 1:
            raise IdlError(f"{tok.where()}: unknown type '{spelled}'")
        full = self.lookup(scope, tok.text, self.types)
        if full is None:
            raise IdlError(f"{tok.where()}: unknown type '{tok.text}' (define it before use)")
        return full

    def member(self, scope):
        type_name = self.type_spec(scope)
        fields = []
        while True:
            name = self.name()
            dims = self.dims(scope)
            fields.append((name, dims))
            sep = self.next()
            if sep.text == ";":
                break
            if sep.text != ",":
                raise IdlError(f"{sep.where()}: expected ';' after field '{name.text}'")
        comment = self.trailing_comment(sep.line)
        unit, description = "", comment
        m = UNIT_COMMENT.match(comment)
        if m:
            unit, description = m.group(1).strip(), m.group(2).strip()
        result = []
        for name, dims in fields:
            base, alias_dims = self.resolve(type_name)
            result.append(Field(name.text, base, alias_dims + dims, unit, description, name.where()))
        return result

    def resolve(self, type_name):
        """Follows typedefs: (non-alias type, extra leading dimensions)."""
        dims = []
        while isinstance(self.types.get(type_name), tuple):
            _, type_name, alias_dims = self.types[type_name]
            dims = dims + alias_dims
        return type_name, dims

    @staticmethod
    def lookup(scope, name, table):
        """IDL scoping: innermost enclosing module first, then outwards."""
        name = name.lstrip(":")
        for depth in range(len(scope), -1, -1):
            candidate = "::".join(scope[:depth] + [name])
            if candidate in table:
                return candidate
        return None


# -- code generation ---------------------------------------------------------

def cpp_string(text):
    return '"' + text.replace("\\", "\\\\").replace('"', '\\"') + '"'


NUMERIC = PRIMITIVES - {"char", "wchar", "string", "long double"}


def leaves(parser, field, prefix="", base="v"):
    """(name, C++ lvalue, unit, description) of every JSON leaf of a field, in toJson
    order; the lvalue is None where setLeaf cannot set it (text, enumerations)."""
    is_char = field.type_name == "char"
    dims = field.dims[:-1] if is_char and field.dims else field.dims
    pairs = [(prefix + field.name, f"{base}.{field.name}()")]
    for n in dims:
        pairs = [(f"{name}[{i}]", f"{expr}[{i}]") for name, expr in pairs for i in range(n)]
    entity = parser.types.get(field.type_name)
    out = []
    for name, expr in pairs:
        if isinstance(entity, Struct):
            for sub in entity.fields:
                out.extend(leaves(parser, sub, name + ".", expr))
        else:
            numeric = field.type_name in NUMERIC and not is_char
            out.append((name, expr if numeric else None, field.unit, field.description))
    return out


def leaf_access_code(parser, s):
    """leafValue/setLeaf of a struct: one case per numeric leaf."""
    access = [lvalue for f in s.fields for _, lvalue, _, _ in leaves(parser, f)]
    get = [f"template <> std::optional<double> leafValue<{s.cpp}>(const {s.cpp}& v, std::size_t leaf) {{\n",
           "  switch (leaf) {\n"]
    put = [f"template <> bool setLeaf<{s.cpp}>({s.cpp}& v, std::size_t leaf, double value) {{\n",
           "  switch (leaf) {\n"]
    for i, a in enumerate(access):
        if a is None:
            continue
        get.append(f"    case {i}: return static_cast<double>({a});\n")
        put.append(f"    case {i}: return assign({a}, value);\n")
    get.append("    default: return std::nullopt;\n  }\n}\n\n")
    put.append("    default: return false;\n  }\n}\n\n")
    return "".join(get) + "".join(put)


def value_expr(parser, field):
    access = f"v.{field.name}()"
    if field.dims:
        return f"value({access})"  # the array helpers recurse element by element
    entity = parser.types.get(field.type_name)
    if isinstance(entity, (Struct, Enum)):
        return f"toJson({access})"
    if field.type_name == "char":
        return f"std::string(1, {access})"
    return access


def namespaces(scope):
    if not scope:
        return "", ""
    name = "::".join(scope)
    return f"namespace {name} {{", f"}}  // namespace {name}"


def by_scope(entities):
    """Consecutive entities of one module, grouped: [(scope, [entity...])]."""
    groups = []
    for e in entities:
        if groups and groups[-1][0] == e.scope:
            groups[-1][1].append(e)
        else:
            groups.append((e.scope, [e]))
    return groups


def common_scope(entities):
    scopes = [e.scope for e in entities]
    common = []
    for parts in zip(*scopes):
        if len(set(parts)) != 1:
            break
        common.append(parts[0])
    return common


def enum_code(e):
    out = [f"std::string_view toString({e.name} v) {{\n  switch (v) {{\n"]
    for value in e.values:
        out.append(f"    case {e.name}::{value}: return {cpp_string(value)};\n")
    out.append("  }\n  return \"?\";\n}\n\n")
    out.append(f"nlohmann::ordered_json toJson({e.name} v) {{\n"
               "  const auto text = toString(v);\n"
               "  if (text == \"?\") return static_cast<std::uint64_t>(v);\n"
               "  return std::string(text);\n}\n\n")
    return "".join(out)


def holds_floating(parser, type_name):
    """Whether a value of the type can hold a NaN: a float, or a struct with one."""
    entity = parser.types.get(type_name)
    if isinstance(entity, Struct):
        return any(holds_floating(parser, f.type_name) for f in entity.fields)
    return type_name in ("double", "float", "long double")


def struct_code(parser, s):
    out = [f"nlohmann::ordered_json toJson(const {s.name}& v) {{\n  nlohmann::ordered_json j;\n"]
    for f in s.fields:
        out.append(f"  j[{cpp_string(f.name)}] = {value_expr(parser, f)};\n")
    out.append("  return j;\n}\n\n")
    out.append(f"const char* firstNonFinite(const {s.name}& v) {{\n")
    for f in s.fields:
        if not holds_floating(parser, f.type_name):
            continue
        out.append(f"  if (!finite(v.{f.name}())) return {cpp_string(f.name)};\n")
    out.append("  return nullptr;\n}\n\n")
    return "".join(out)


def generate(parser, idl_files, name, include_prefix):
    structs = [e for e in parser.order if isinstance(e, Struct)]
    enums = [e for e in parser.order if isinstance(e, Enum)]
    meta_scope = common_scope(parser.order)
    meta_ns = "::".join(meta_scope)
    sources = ", ".join(os.path.basename(f) for f in idl_files)
    includes = "".join(
        f'#include "{include_prefix}/{os.path.splitext(os.path.basename(f))[0]}.h"\n'
        for f in idl_files)

    h = [f"// Generated by idl/gen_json.py from {sources}: do not edit.\n",
         "#pragma once\n#include <cstddef>\n#include <optional>\n#include <string_view>\n#include <vector>\n\n",
         "#include <nlohmann/json.hpp>\n\n", includes, "\n"]
    open_ns, close_ns = namespaces(meta_scope)
    h.append(f"{open_ns}\n\n")
    h.append("/// One field of an IDL struct, from its `// [unit] meaning` comment.\n"
             "struct FieldInfo {\n"
             "  std::string_view name;         ///< field, or leaf path (\"header.step\", \"b_body_T[0]\")\n"
             "  std::string_view unit;         ///< unit as written in the IDL; empty: none given\n"
             "  std::string_view description;  ///< the rest of the comment\n"
             "};\n\n"
             "/// The direct fields of an IDL struct, in IDL order.\n"
             "template <class T> const std::vector<FieldInfo>& fieldUnits();\n"
             "/// The leaves of toJson(T) in order: nested structs and arrays expanded,\n"
             "/// char arrays one leaf. Flattening toJson(sample) gives the same sequence.\n"
             "template <class T> const std::vector<FieldInfo>& leafFields();\n"
             "/// The IDL's scoped name of a struct or enum.\n"
             "template <class T> std::string_view idlName();\n"
             "/// Leaf `leaf` of leafFields<T>() as a number (a boolean as 0 or 1); nullopt for\n"
             "/// text, an enumeration or an index past the end.\n"
             "template <class T> std::optional<double> leafValue(const T& sample, std::size_t leaf);\n"
             "/// Sets that leaf: a boolean to value != 0, an integer only to a whole value within\n"
             "/// its type's range, a float to any value it can hold. false, and the sample unchanged, for\n"
             "/// any other leaf or value (a generic writer, e.g. a device bridge, checks this).\n"
             "template <class T> bool setLeaf(T& sample, std::size_t leaf, double value);\n\n")
    for s in structs:
        h.append(f"template <> const std::vector<FieldInfo>& fieldUnits<{s.cpp}>();\n")
        h.append(f"template <> const std::vector<FieldInfo>& leafFields<{s.cpp}>();\n")
        h.append(f"template <> std::optional<double> leafValue<{s.cpp}>(const {s.cpp}& v, std::size_t leaf);\n")
        h.append(f"template <> bool setLeaf<{s.cpp}>({s.cpp}& v, std::size_t leaf, double value);\n")
    for e in parser.order:
        h.append(f"template <> std::string_view idlName<{e.cpp}>();\n")
    h.append(f"\n{close_ns}\n\n")
    for scope, group in by_scope(parser.order):
        o, c = namespaces(scope)
        h.append(f"{o}\n\n")
        for e in group:
            if isinstance(e, Enum):
                h.append(f"/// The enumerator's name; \"?\" for a value the IDL does not list.\n"
                         f"std::string_view toString({e.name} v);\n"
                         f"/// The enumerator's name (its number when unlisted).\n"
                         f"nlohmann::ordered_json toJson({e.name} v);\n")
            else:
                h.append(f"nlohmann::ordered_json toJson(const {e.name}& v);\n"
                         f"/// The first field holding a NaN or an infinity (a leaf path as in\n"
                         f"/// leafFields, \"b_body_T\"); nullptr when every value is finite.\n"
                         f"const char* firstNonFinite(const {e.name}& v);\n")
        h.append(f"\n{c}\n")

    cpp = [f"// Generated by idl/gen_json.py from {sources}: do not edit.\n",
           f'#include "{include_prefix}/{name}.hpp"\n\n',
           "#include <array>\n#include <cmath>\n#include <cstring>\n#include <limits>\n#include <string>\n#include <type_traits>\n\n",
           "namespace {\n\n",
           "template <class T> nlohmann::ordered_json value(const T& v);\n",
           "template <std::size_t N> nlohmann::ordered_json value(const std::array<char, N>& a);\n",
           "template <class T, std::size_t N> nlohmann::ordered_json value(const std::array<T, N>& a);\n\n",
           "template <class T> nlohmann::ordered_json value(const T& v) {\n"
           "  if constexpr (std::is_same_v<T, char>) {\n"
           "    return std::string(1, v);\n"
           "  } else if constexpr (std::is_arithmetic_v<T> || std::is_same_v<T, std::string>) {\n"
           "    return v;\n"
           "  } else {\n"
           "    return toJson(v);\n"
           "  }\n"
           "}\n\n"
           "/// A char array is text, NUL padded.\n"
           "template <std::size_t N> nlohmann::ordered_json value(const std::array<char, N>& a) {\n"
           "  return std::string(a.data(), ::strnlen(a.data(), N));\n"
           "}\n\n"
           "template <class T, std::size_t N> nlohmann::ordered_json value(const std::array<T, N>& a) {\n"
           "  auto out = nlohmann::ordered_json::array();\n"
           "  for (const auto& x : a) out.push_back(value(x));\n"
           "  return out;\n"
           "}\n\n",
           "/// Whether every floating-point value in v is finite (integers, text and\n"
           "/// enumerations always are).\n"
           "template <class T> bool finite(const T& v) {\n"
           "  if constexpr (std::is_floating_point_v<T>) {\n"
           "    return std::isfinite(v);\n"
           "  } else if constexpr (std::is_arithmetic_v<T> || std::is_enum_v<T>) {\n"
           "    return true;\n"
           "  } else {\n"
           "    return firstNonFinite(v) == nullptr;\n"
           "  }\n"
           "}\n\n"
           "template <class T, std::size_t N> bool finite(const std::array<T, N>& a) {\n"
           "  for (const auto& x : a) {\n"
           "    if (!finite(x)) return false;\n"
           "  }\n"
           "  return true;\n"
           "}\n\n",
           "/// setLeaf's conversion: nothing is rounded, wrapped or clipped on the way in.\n"
           "template <class T> bool assign(T& target, double value) {\n"
           "  if constexpr (std::is_same_v<T, bool>) {\n"
           "    target = value != 0.0;\n"
           "  } else if constexpr (std::is_integral_v<T>) {\n"
           "    // 2^63 and 2^64 are exact doubles: the bounds below are exclusive of them.\n"
           "    const double top = 2.0 * static_cast<double>(std::numeric_limits<T>::max() / 2 + 1);\n"
           "    if (!(value == std::trunc(value) && value >= static_cast<double>(std::numeric_limits<T>::min()) &&\n"
           "          value < top)) {\n"
           "      return false;\n"
           "    }\n"
           "    target = static_cast<T>(value);\n"
           "  } else {\n"
           "    // A finite double beyond a float's range would become infinite.\n"
           "    if (std::isfinite(value) && std::abs(value) > static_cast<double>(std::numeric_limits<T>::max())) return false;\n"
           "    target = static_cast<T>(value);\n"
           "  }\n"
           "  return true;\n"
           "}\n\n",
           "}  // namespace\n\n"]
    for scope, group in by_scope(parser.order):
        o, c = namespaces(scope)
        cpp.append(f"{o}\n\n")
        for e in group:
            cpp.append(enum_code(e) if isinstance(e, Enum) else struct_code(parser, e))
        cpp.append(f"{c}\n\n")

    o, c = namespaces(meta_scope)
    cpp.append(f"{o}\n\n")
    for s in structs:
        cpp.append(f"template <> const std::vector<FieldInfo>& fieldUnits<{s.cpp}>() {{\n"
                   "  static const std::vector<FieldInfo> fields{\n")
        for f in s.fields:
            cpp.append(f"      {{{cpp_string(f.name)}, {cpp_string(f.unit)}, "
                       f"{cpp_string(f.description)}}},\n")
        cpp.append("  };\n  return fields;\n}\n\n")
        cpp.append(f"template <> const std::vector<FieldInfo>& leafFields<{s.cpp}>() {{\n"
                   "  static const std::vector<FieldInfo> fields{\n")
        for f in s.fields:
            for leaf, _, unit, description in leaves(parser, f):
                cpp.append(f"      {{{cpp_string(leaf)}, {cpp_string(unit)}, "
                           f"{cpp_string(description)}}},\n")
        cpp.append("  };\n  return fields;\n}\n\n")
        cpp.append(leaf_access_code(parser, s))
    for e in parser.order:
        cpp.append(f"template <> std::string_view idlName<{e.cpp}>() {{ "
                   f"return {cpp_string(e.cpp)}; }}\n")
    cpp.append(f"\n{c}\n")
    return "".join(h), "".join(cpp)


def write_if_changed(path, text):
    """Leaves an unchanged file alone, so its dependants are not rebuilt."""
    try:
        with open(path, encoding="utf-8") as f:
            if f.read() == text:
                os.utime(path)
                return
    except FileNotFoundError:
        pass
    with open(path, "w", encoding="utf-8") as f:
        f.write(text)


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("-o", "--out", required=True, help="output directory")
    ap.add_argument("--name", default="MsgJson", help="output base name (NAME.hpp, NAME.cpp)")
    ap.add_argument("--include-prefix", default="msg",
                    help="include path of the generated headers (msg/Truth.h)")
    ap.add_argument("idl", nargs="+", help="IDL files, every file a type depends on")
    args = ap.parse_args(argv)

    parser = Parser()
    parsed = []
    try:
        for path in args.idl:
            parser.parse_file(path, parsed)
        if not parser.order:
            raise IdlError("no struct or enum in " + " ".join(args.idl))
        header, source = generate(parser, parsed, args.name, args.include_prefix)
    except (IdlError, OSError) as e:
        print(f"gen_json.py: error: {e}", file=sys.stderr)
        return 1
    os.makedirs(args.out, exist_ok=True)
    write_if_changed(os.path.join(args.out, args.name + ".hpp"), header)
    write_if_changed(os.path.join(args.out, args.name + ".cpp"), source)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
