// Files, units and messages around the shape conversions in convert.h
// (spec/exchange.md).
#include "io/occt/exchange.h"

#include "io/occt/convert.h"
#include "io/occt/messages.h"
#include "io/occt/step_references.h"
#include "geometry/occt/freeform_occt.h"

#include <BRepCheck.hxx>
#include <BRepCheck_Analyzer.hxx>
#include <BRepCheck_ListOfStatus.hxx>
#include <BRepCheck_Result.hxx>
#include <BRepTools.hxx>
#include <BRep_Builder.hxx>
#include <IFSelect_ReturnStatus.hxx>
#include <IGESControl_Controller.hxx>
#include <IGESControl_Reader.hxx>
#include <IGESControl_Writer.hxx>
#include <IGESData_GlobalSection.hxx>
#include <IGESData_IGESModel.hxx>
#include <Interface_Static.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <STEPControl_Reader.hxx>
#include <STEPControl_Writer.hxx>
#include <StepData_StepModel.hxx>
#include <Standard_Failure.hxx>
#include <TColStd_SequenceOfAsciiString.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS.hxx>
#include <Transfer_TransientProcess.hxx>
#include <XSControl_TransferReader.hxx>
#include <XSControl_WorkSession.hxx>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <sstream>

namespace kintsugi::io {

// OpenCASCADE prints translation chatter to stdout through its default messenger;
// the CLI's output is ours, so it goes.
void occt::silence_occt() {
  static std::once_flag once;
  std::call_once(once, [] {
    Handle(Message_Messenger) m = Message::DefaultMessenger();
    m->RemovePrinters(STANDARD_TYPE(Message_Printer));
  });
}

std::string occt::status_name(BRepCheck_Status s) {
  std::ostringstream os;
  BRepCheck::Print(s, os);
  std::string n = os.str();
  while (!n.empty() && std::isspace(static_cast<unsigned char>(n.back()))) n.pop_back();
  return n;
}

namespace {

using occt::silence_occt;
using occt::status_name;

// OpenCASCADE's STEP interface keeps its settings in process-wide statics
// (Interface_Static); one STEP transfer at a time.
std::mutex& step_mutex() {
  static std::mutex m;
  return m;
}

std::string lower(std::string s) {
  for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

struct LengthUnit {
  const char* short_name;  // ours: what CadImport::units and export_cad's `units` say
  const char* step_name;   // the write.step.unit value
  double mm;
};
// SI prefixes with "metre" and the conversion-based units STEP files use.
const LengthUnit kUnits[] = {
    {"mm", "MM", 1.0},       {"cm", "CM", 10.0},        {"m", "M", 1000.0},    {"km", "KM", 1e6},
    {"um", "UM", 1e-3},      {"in", "INCH", 25.4},      {"ft", "FT", 304.8},   {"mi", "MI", 1609344.0},
    {"mil", "MIL", 0.0254},  {"uin", "UIN", 2.54e-5},
};

const LengthUnit* unit_by_short_name(const std::string& s) {
  std::string l = lower(s);
  if (l == "inch" || l == "inches") l = "in";
  if (l == "foot" || l == "feet") l = "ft";
  if (l == "micron" || l == "µm") l = "um";
  for (const LengthUnit& u : kUnits)
    if (l == u.short_name) return &u;
  return nullptr;
}

// A unit name as STEPControl_Reader::FileUnits gives it: an SI prefix + "metre", or the
// name of a conversion-based unit ("INCH", "FOOT").
const LengthUnit* unit_by_file_name(const std::string& s) {
  std::string l = lower(s);
  static const std::map<std::string, std::string> names = {
      {"millimetre", "mm"}, {"millimeter", "mm"}, {"centimetre", "cm"}, {"centimeter", "cm"},
      {"metre", "m"},       {"meter", "m"},       {"kilometre", "km"},  {"kilometer", "km"},
      {"micrometre", "um"}, {"micrometer", "um"}, {"inch", "in"},       {"foot", "ft"},
      {"feet", "ft"},       {"mile", "mi"},       {"mil", "mil"},       {"thou", "mil"},
      {"microinch", "uin"},
  };
  auto it = names.find(l);
  return it == names.end() ? nullptr : unit_by_short_name(it->second);
}

bool fail(std::string* error, std::string msg) {
  if (error) *error = std::move(msg);
  return false;
}

// Missing, unreadable and empty files are refused before OpenCASCADE sees them.
bool check_file(const std::string& path, std::string* text_head, std::string* text_tail, std::string* error,
                std::string* whole = nullptr) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) return fail(error, path + ": no such file");
  if (std::filesystem::is_directory(path, ec)) return fail(error, path + ": is a directory, not a file");
  auto size = std::filesystem::file_size(path, ec);
  if (ec) return fail(error, path + ": cannot read the file size: " + ec.message());
  std::ifstream in(path, std::ios::binary);
  if (!in) return fail(error, path + ": cannot be opened for reading");
  std::string all((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  auto not_space = [](char c) { return !std::isspace(static_cast<unsigned char>(c)); };
  if (size == 0 || std::none_of(all.begin(), all.end(), not_space)) return fail(error, path + ": the file is empty");
  auto b = std::find_if(all.begin(), all.end(), not_space);
  auto e = std::find_if(all.rbegin(), all.rend(), not_space).base();
  std::string trimmed(b, e);
  *text_head = trimmed.substr(0, 64);
  *text_tail = trimmed.size() > 64 ? trimmed.substr(trimmed.size() - 64) : trimmed;
  if (whole) *whole = std::move(all);
  return true;
}

std::optional<CadImport> import_step(const std::string& path, std::string* error) {
  std::string head, tail, text;
  if (!check_file(path, &head, &tail, error, &text)) return std::nullopt;
  if (head.rfind("ISO-10303-21", 0) != 0)
    return fail(error, path + ": not a STEP file (it does not start with ISO-10303-21;)"), std::nullopt;
  if (tail.size() < 17 || tail.find("END-ISO-10303-21") == std::string::npos)
    return fail(error, path + ": the STEP file is truncated (no END-ISO-10303-21; at its end)"), std::nullopt;
  // OpenCASCADE would drop the entity silently (a face gone, a hole in the model).
  if (std::string why = step_dangling_reference(text); !why.empty())
    return fail(error, path + ": the STEP file is corrupt: " + why), std::nullopt;
  text = std::string();

  std::lock_guard<std::mutex> lock(step_mutex());
  STEPControl_Reader reader;
  IFSelect_ReturnStatus st = reader.ReadFile(path.c_str());
  if (st != IFSelect_RetDone)
    return fail(error, path + ": the STEP file cannot be parsed (it is corrupt or not STEP)"), std::nullopt;

  CadImport out;
  TColStd_SequenceOfAsciiString lengths, angles, solids;
  reader.FileUnits(lengths, angles, solids);
  const LengthUnit* unit = nullptr;
  if (lengths.Length() > 0) {
    std::string name = lengths.Value(1).ToCString();
    unit = unit_by_file_name(name);
    if (!unit)
      out.warnings.push_back("length unit '" + name + "' is not recognised: geometry converted to millimetres");
    for (int i = 2; i <= lengths.Length(); ++i)
      if (lower(lengths.Value(i).ToCString()) != lower(name))
        out.warnings.push_back(std::string("the file uses several length units (") + name + ", " +
                               lengths.Value(i).ToCString() + "): geometry is in " +
                               (unit ? unit->short_name : "mm"));
  } else {
    out.warnings.push_back("the file declares no length unit: millimetres assumed");
  }
  if (!unit) unit = unit_by_short_name("mm");
  // Transfer without scaling: the system unit is the file's unit.
  reader.SetSystemLengthUnit(unit->mm);
  out.units = unit->short_name;
  out.unit_in_mm = unit->mm;

  int roots = reader.NbRootsForTransfer();
  if (roots == 0) return fail(error, path + ": the STEP file holds no shape (no transferable root entity)"), std::nullopt;
  reader.TransferRoots();
  TopoDS_Shape shape = reader.OneShape();
  if (shape.IsNull())
    return fail(error, path + ": the STEP file holds no shape (" + std::to_string(roots) +
                           " root entities, none gave a shape)"),
           std::nullopt;

  Handle(XSControl_TransferReader) tr = reader.WS()->TransferReader();
  Handle(Interface_InterfaceModel) model = reader.WS()->Model();
  occt::FaceLocator locate = [&](const TopoDS_Shape& face, int index) {
    std::string s = "face #" + std::to_string(index);
    Handle(Standard_Transient) ent = tr.IsNull() ? nullptr : tr->EntityFromShapeResult(face, 1);
    if (ent.IsNull() && !tr.IsNull()) ent = tr->EntityFromShapeResult(face, -1);
    if (!ent.IsNull() && !model.IsNull() && model->Number(ent) > 0)
      s += " (STEP entity #" + std::to_string(model->Number(ent)) + ")";
    return s;
  };
  std::string why;
  std::optional<Body> body = occt::from_shape(shape, locate, &out.warnings, &why);
  if (!body) return fail(error, path + ": " + why), std::nullopt;
  out.body = std::move(*body);
  return out;
}

// BRepTools::Read does not stop at the end of a truncated file (it can loop forever),
// so the shape section is checked first: "TShapes n", n records (a type line, ..., a
// line ending in '*'), then the root shape ("+1 0").
bool brep_complete(const std::string& path, std::string* why) {
  std::ifstream in(path, std::ios::binary);
  std::string line;
  long declared = -1, records = 0;
  bool in_record = false, root = false;
  static const char* kTypes[] = {"Ve", "Ed", "Wi", "Fa", "Sh", "So", "CS", "Co"};
  while (std::getline(in, line)) {
    while (!line.empty() && std::isspace(static_cast<unsigned char>(line.back()))) line.pop_back();
    if (declared < 0) {
      if (line.rfind("TShapes ", 0) == 0) {
        try {
          declared = std::stol(line.substr(8));
        } catch (const std::exception&) {
          return *why = "the shape count after 'TShapes' is not a number", false;
        }
        if (declared < 0) return *why = "a negative shape count", false;
      }
      continue;
    }
    if (root) continue;
    if (!in_record && records == declared) {
      if (!line.empty() && (line[0] == '+' || line[0] == '-')) root = true;
      continue;
    }
    if (!in_record) {
      if (std::find(std::begin(kTypes), std::end(kTypes), line) != std::end(kTypes)) in_record = true;
      continue;
    }
    if (!line.empty() && line.back() == '*') {
      in_record = false;
      ++records;
    }
  }
  if (declared < 0) return *why = "no shape section (no 'TShapes' line)", false;
  if (records < declared || !root)
    return *why = "the shape section ends after " + std::to_string(records) + " of its " + std::to_string(declared) +
                  " shapes" + (records == declared ? " (no root shape)" : ""),
           false;
  return true;
}

// `out` with the body converted from `shape` (faces named by their index in the file),
// or the conversion's refusal naming `path`.
std::optional<CadImport> with_body(const TopoDS_Shape& shape, const std::string& path, CadImport out,
                                   std::string* error) {
  occt::FaceLocator locate = [](const TopoDS_Shape&, int index) { return "face #" + std::to_string(index); };
  std::string why;
  std::optional<Body> body = occt::from_shape(shape, locate, &out.warnings, &why);
  if (!body) return fail(error, path + ": " + why), std::nullopt;
  out.body = std::move(*body);
  return out;
}

std::optional<CadImport> import_brep(const std::string& path, std::string* error) {
  std::string head, tail;
  if (!check_file(path, &head, &tail, error)) return std::nullopt;
  if (head.find("CASCADE Topology") == std::string::npos)
    return fail(error, path + ": not an OpenCASCADE BREP file (no 'CASCADE Topology' header)"), std::nullopt;
  if (std::string why; !brep_complete(path, &why))
    return fail(error, path + ": the BREP file is truncated or corrupt: " + why), std::nullopt;
  TopoDS_Shape shape;
  BRep_Builder bb;
  if (!BRepTools::Read(shape, path.c_str(), bb) || shape.IsNull())
    return fail(error, path + ": the BREP file is truncated or corrupt (OpenCASCADE could not read a shape)"),
           std::nullopt;
  return with_body(shape, path, CadImport{}, error);  // BREP files carry no unit: millimetres by convention
}

// IGES global-section unit flags (IGES 5.3, section 2.2.4.3, parameter 14).
const LengthUnit* iges_unit(int flag) {
  switch (flag) {
    case 1: return unit_by_short_name("in");
    case 2: return unit_by_short_name("mm");
    case 4: return unit_by_short_name("ft");
    case 5: return unit_by_short_name("mi");
    case 6: return unit_by_short_name("m");
    case 7: return unit_by_short_name("km");
    case 8: return unit_by_short_name("mil");
    case 9: return unit_by_short_name("um");
    case 10: return unit_by_short_name("cm");
    case 11: return unit_by_short_name("uin");
    default: return nullptr;
  }
}

int iges_flag(const LengthUnit& u) {
  for (int f = 1; f <= 11; ++f)
    if (iges_unit(f) == &u) return f;
  return 2;
}

std::optional<CadImport> import_iges(const std::string& path, std::string* error) {
  std::string head, tail;
  if (!check_file(path, &head, &tail, error)) return std::nullopt;
  // Fixed 80-column records; column 73 of the first line is the section letter S (or G
  // for a file without a start section).
  std::ifstream in(path, std::ios::binary);
  std::string first;
  std::getline(in, first);
  while (!first.empty() && (first.back() == '\r' || first.back() == '\n')) first.pop_back();
  if (first.size() < 73 || (first[72] != 'S' && first[72] != 'G'))
    return fail(error, path + ": not an IGES file (no start or global section in columns 73-80)"), std::nullopt;
  if (tail.size() < 8 || tail.find('T', tail.size() > 8 ? tail.size() - 8 : 0) == std::string::npos)
    return fail(error, path + ": the IGES file is truncated (no terminate section at its end)"), std::nullopt;

  std::lock_guard<std::mutex> lock(step_mutex());  // IGES settings are process-wide statics too
  IGESControl_Controller::Init();
  IGESControl_Reader reader;
  if (reader.ReadFile(path.c_str()) != IFSelect_RetDone)
    return fail(error, path + ": the IGES file cannot be parsed (it is corrupt or not IGES)"), std::nullopt;
  CadImport out;
  const LengthUnit* unit = nullptr;
  Handle(IGESData_IGESModel) model = reader.IGESModel();
  if (!model.IsNull()) unit = iges_unit(model->GlobalSection().UnitFlag());
  if (!unit) {
    out.warnings.push_back("the IGES file's length unit is not recognised: millimetres assumed");
    unit = unit_by_short_name("mm");
  }
  // Transfer without scaling: the target unit is the file's.
  Interface_Static::SetCVal("xstep.cascade.unit", unit->step_name);
  out.units = unit->short_name;
  out.unit_in_mm = unit->mm;
  reader.SetReadVisible(Standard_True);
  int roots = reader.NbRootsForTransfer();
  if (roots == 0) return fail(error, path + ": the IGES file holds no shape (no transferable entity)"), std::nullopt;
  reader.TransferRoots();
  TopoDS_Shape shape = reader.OneShape();
  Interface_Static::SetCVal("xstep.cascade.unit", "MM");
  if (shape.IsNull())
    return fail(error, path + ": the IGES file holds no shape (" + std::to_string(roots) + " root entities, none gave a shape)"),
           std::nullopt;
  // IGES trimmed surfaces come as separate faces: sew them into shells first (the
  // tolerance is the file's resolution, at least 1e-6 of the file's unit).
  double resolution = model.IsNull() ? 1e-6 : std::max(1e-6, model->GlobalSection().Resolution());
  shape = occt::sew_faces(shape, resolution, &out.warnings);
  return with_body(shape, path, std::move(out), error);
}

bool write_iges(const TopoDS_Shape& shape, const std::string& path, const std::string& units, std::string* error) {
  const LengthUnit* unit = unit_by_short_name(units);
  if (!unit) return fail(error, "unknown length unit '" + units + "' (mm, cm, m, km, um, in, ft, mi, mil, uin)");
  std::lock_guard<std::mutex> lock(step_mutex());
  IGESControl_Controller::Init();
  // BRep mode (faces, shells and solids as MSBO entities 186/514/510): the topology is
  // written as it is, not as unconnected trimmed surfaces.
  const int previous_mode = Interface_Static::IVal("write.iges.brep.mode");
  struct Restore {
    int mode;
    ~Restore() { Interface_Static::SetIVal("write.iges.brep.mode", mode); }
  } restore{previous_mode};
  Interface_Static::SetIVal("write.iges.brep.mode", 1);
  Interface_Static::SetCVal("xstep.cascade.unit", unit->step_name);
  IGESControl_Writer writer(unit->step_name, 1);
  writer.Model()->ChangeGlobalSection().SetUnitFlag(iges_flag(*unit));
  bool added = writer.AddShape(shape);
  Interface_Static::SetCVal("xstep.cascade.unit", "MM");
  if (!added) return fail(error, path + ": OpenCASCADE could not translate the shape to IGES");
  writer.ComputeModel();
  if (!writer.Write(path.c_str())) return fail(error, path + ": cannot write the IGES file");
  return true;
}

bool write_step(const TopoDS_Shape& shape, const std::string& path, const std::string& units, std::string* error) {
  const LengthUnit* unit = unit_by_short_name(units);
  if (!unit) return fail(error, "unknown length unit '" + units + "' (mm, cm, m, km, um, in, ft, mi, mil, uin)");
  std::lock_guard<std::mutex> lock(step_mutex());
  STEPControl_Writer writer;
  // Process-wide: put back what it was, so that a later STEP write in this process
  // (another library's, a test's) is not written in our unit.
  const std::string previous_unit = Interface_Static::CVal("write.step.unit");
  struct Restore {
    const std::string& unit;
    ~Restore() { Interface_Static::SetCVal("write.step.unit", unit.c_str()); }
  } restore{previous_unit};
  Interface_Static::SetCVal("write.step.unit", unit->step_name);
  // Our coordinates are already in `units`: local and written unit are the same, so
  // nothing is scaled.
  writer.Model()->SetLocalLengthUnit(unit->mm);
  writer.Model()->SetWriteLengthUnit(unit->mm);
  if (writer.Transfer(shape, STEPControl_AsIs) != IFSelect_RetDone)
    return fail(error, path + ": OpenCASCADE could not translate the shape to STEP");
  if (writer.Write(path.c_str()) != IFSelect_RetDone) return fail(error, path + ": cannot write the STEP file");
  return true;
}

}  // namespace

std::optional<CadImport> import_cad(const std::string& path, CadFormat f, std::string* error) {
  silence_occt();
  geo::occt::register_freeform_backend();
  try {
    switch (f) {
      case CadFormat::step: return import_step(path, error);
      case CadFormat::iges: return import_iges(path, error);
      case CadFormat::brep: return import_brep(path, error);
    }
    return fail(error, path + ": unknown format"), std::nullopt;
  } catch (const Standard_Failure& e) {
    fail(error, path + ": OpenCASCADE failed while reading: " + e.GetMessageString());
  } catch (const std::exception& e) {
    fail(error, path + ": reading failed: " + e.what());
  }
  return std::nullopt;
}

bool export_cad(const Body& b, const std::string& path, CadFormat f, std::string* error, const std::string& units,
                double precision) {
  silence_occt();
  geo::occt::register_freeform_backend();
  try {
    std::string why;
    std::optional<occt::BuiltShape> s = occt::to_shape(b, &why, nullptr, nullptr, precision);
    if (!s) return fail(error, path + ": cannot convert the body: " + why);
    if (f == CadFormat::step) return write_step(s->shape, path, units, error);
    if (f == CadFormat::iges) return write_iges(s->shape, path, units, error);
    if (!unit_by_short_name(units))
      return fail(error, "unknown length unit '" + units + "' (mm, cm, m, km, um, in, ft, mi, mil, uin)");
    if (!BRepTools::Write(s->shape, path.c_str())) return fail(error, path + ": cannot write the BREP file");
    return true;
  } catch (const Standard_Failure& e) {
    return fail(error, path + ": OpenCASCADE failed while writing: " + e.GetMessageString());
  } catch (const std::exception& e) {
    return fail(error, path + ": writing failed: " + e.what());
  }
}

OcctVerdict occt_check(const Body& b, double precision) {
  silence_occt();
  geo::occt::register_freeform_backend();
  OcctVerdict v{false, {}};
  try {
    std::string why;
    std::optional<occt::BuiltShape> s = occt::to_shape(b, &why, nullptr, nullptr, precision);
    if (!s) {
      v.problems.push_back("cannot convert the body: " + why);
      return v;
    }
    // Names for the sub-shapes, from the element each came from.
    std::vector<std::pair<TopoDS_Shape, std::string>> named;
    auto add = [&](const occt::ShapeSlots& shapes, const char* prefix, const char* what) {
      shapes.for_each([&](std::size_t i, const TopoDS_Shape& shape) {
        named.emplace_back(shape, std::string(what) + " " + prefix + std::to_string(i));
      });
    };
    add(s->vertex, "v", "vertex");
    add(s->edge, "e", "edge");
    add(s->loop_wire, "l", "wire of loop");
    add(s->face, "f", "face");
    add(s->shell, "s", "shell");
    add(s->solid, "s", "solid of shell");
    auto name_of = [&](const TopoDS_Shape& sh) -> std::string {
      for (const auto& [shape, name] : named)
        if (shape.IsSame(sh)) return name;
      switch (sh.ShapeType()) {
        case TopAbs_EDGE: return "an edge OpenCASCADE added (degenerated at a pole)";
        case TopAbs_COMPOUND: return "the compound";
        default: return "a sub-shape OpenCASCADE added";
      }
    };
    BRepCheck_Analyzer ana(s->shape);
    v.valid = ana.IsValid() == Standard_True;
    if (v.valid) return v;
    TopTools_IndexedMapOfShape all;
    all.Add(s->shape);
    TopExp::MapShapes(s->shape, all);
    for (int i = 1; i <= all.Extent(); ++i) {
      const TopoDS_Shape& sub = all(i);
      Handle(BRepCheck_Result) r = ana.Result(sub);
      if (r.IsNull()) continue;
      for (BRepCheck_ListIteratorOfListOfStatus it(r->Status()); it.More(); it.Next())
        if (it.Value() != BRepCheck_NoError) v.problems.push_back(name_of(sub) + ": " + status_name(it.Value()));
      for (r->InitContextIterator(); r->MoreShapeInContext(); r->NextShapeInContext())
        for (BRepCheck_ListIteratorOfListOfStatus it(r->StatusOnShape()); it.More(); it.Next())
          if (it.Value() != BRepCheck_NoError)
            v.problems.push_back(name_of(sub) + " in " + name_of(r->ContextualShape()) + ": " + status_name(it.Value()));
    }
    if (v.problems.empty()) v.problems.push_back("BRepCheck_Analyzer reports the shape invalid without a status");
  } catch (const Standard_Failure& e) {
    v.valid = false;
    v.problems.push_back(std::string("OpenCASCADE failed while checking: ") + e.GetMessageString());
  }
  return v;
}

}  // namespace kintsugi::io
