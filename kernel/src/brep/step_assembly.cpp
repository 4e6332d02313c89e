#include "steady/brep/step_assembly.hpp"

#include "steady/brep/brep_io.hpp"

#include <IFSelect_ReturnStatus.hxx>
#include <Interface_Check.hxx>
#include <Interface_CheckIterator.hxx>
#include <Interface_CheckTool.hxx>
#include <Interface_InterfaceModel.hxx>
#include <XSControl_WorkSession.hxx>
#include <Interface_Static.hxx>
#include <Quantity_Color.hxx>
#include <StepData_Protocol.hxx>
#include <StepData_StepModel.hxx>
#include <StepData_StepWriter.hxx>
#include <STEPCAFControl_Reader.hxx>
#include <STEPCAFControl_Writer.hxx>
#include <TDF_ChildIterator.hxx>
#include <TDF_Label.hxx>
#include <TDF_LabelSequence.hxx>
#include <TDataStd_Name.hxx>
#include <TDocStd_Document.hxx>
#include <TopLoc_Location.hxx>
#include <XCAFApp_Application.hxx>
#include <XCAFDoc_ColorTool.hxx>
#include <XCAFDoc_DocumentTool.hxx>
#include <XCAFDoc_ShapeTool.hxx>

#include <BRepCheck_Analyzer.hxx>

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <mutex>
#include <sstream>

#include "brep/child_reader.hpp"
#include "brep/connected_face_order.hpp"
#include "brep/occ_progress.hpp"
#include "brep/step_reproducible.hpp"
#include "brep/step_shared_geometry.hpp"
#include "steady/core/errors.hpp"

namespace steady {

namespace {

// XCAF documents come from one application object; creating and closing them is serialized.
std::mutex& xcaf_mutex() {
  static std::mutex m;
  return m;
}

Handle(TDocStd_Document) new_document() {
  Handle(TDocStd_Document) doc;
  XCAFApp_Application::GetApplication()->NewDocument("MDTV-XCAF", doc);
  return doc;
}

// Sets one of OpenCASCADE's process-wide translation settings for a scope and restores it after, so that FreeCAD's
// own STEP export in the same process keeps its settings.
class ScopedStaticInt {
 public:
  ScopedStaticInt(const char* name, int value) : name_(name), old_(Interface_Static::IVal(name)) {
    Interface_Static::SetIVal(name_, value);
  }
  ~ScopedStaticInt() { Interface_Static::SetIVal(name_, old_); }
  ScopedStaticInt(const ScopedStaticInt&) = delete;
  ScopedStaticInt& operator=(const ScopedStaticInt&) = delete;

 private:
  const char* name_;
  int old_;
};

// Closes an XCAF document however the scope is left (errors, Cancelled).
struct DocumentCloser {
  Handle(TDocStd_Document) doc;
  ~DocumentCloser() { XCAFApp_Application::GetApplication()->Close(doc); }
};

std::string label_name(const TDF_Label& label) {
  Handle(TDataStd_Name) name;
  if (!label.FindAttribute(TDataStd_Name::GetID(), name)) return "";
  const TCollection_ExtendedString& s = name->Get();
  std::string out;
  for (int i = 1; i <= s.Length(); ++i) out.push_back(static_cast<char>(s.Value(i)));
  return out;
}

void collect(const Handle(XCAFDoc_ShapeTool)& shapes, const Handle(XCAFDoc_ColorTool)& colors, const TDF_Label& label,
             const TopLoc_Location& placement, const std::string& instance_name, std::vector<StepPart>& out) {
  TDF_Label referred = label;
  TopLoc_Location loc = placement;
  if (XCAFDoc_ShapeTool::IsReference(label)) {
    XCAFDoc_ShapeTool::GetReferredShape(label, referred);
    loc = placement * XCAFDoc_ShapeTool::GetLocation(label);
  }
  if (XCAFDoc_ShapeTool::IsAssembly(referred)) {
    TDF_LabelSequence components;
    XCAFDoc_ShapeTool::GetComponents(referred, components);
    for (int i = 1; i <= components.Length(); ++i)
      collect(shapes, colors, components.Value(i), loc, label_name(components.Value(i)), out);
    return;
  }
  StepPart part;
  part.name = label_name(referred);
  if (part.name.empty()) part.name = instance_name;
  part.shape = XCAFDoc_ShapeTool::GetShape(referred).Moved(loc);
  Quantity_Color c;
  part.has_color = colors->GetColor(referred, XCAFDoc_ColorGen, c) || colors->GetColor(referred, XCAFDoc_ColorSurf, c) ||
                   colors->GetColor(label, XCAFDoc_ColorGen, c) || colors->GetColor(label, XCAFDoc_ColorSurf, c);
  if (part.has_color) part.color = {c.Red(), c.Green(), c.Blue()};
  out.push_back(part);
}

}  // namespace

void check_step_name(const std::string& name, const char* field) {
  if (name.empty()) fail_input(field, "a STEP part name must not be empty");
  if (name.find('\0') != std::string::npos) fail_input(field, "a STEP part name must not contain a NUL character");
  if (name.size() > kMaxStepNameLength)
    fail_input(field, "a STEP part name has at most " + std::to_string(kMaxStepNameLength) + " characters (this one has " +
                          std::to_string(name.size()) + ")");
}

namespace {

// Reals are written to 1e-9 of the model's unit where OpenCASCADE writes 1e-12 (issue 14, item 3: compact files):
// a third of a part's file is numbers, and every edge holds its curves to 1e-7 at best, so the nine decimals keep
// them 100 times finer than that. Values from 1e-3 to 1e7 take that fixed form; smaller and larger ones keep
// OpenCASCADE's 13 significant digits (trailing zeros are dropped either way).
constexpr const char* kFixedRealFormat = "%.9f";
constexpr double kFixedRealFrom = 1e-3, kFixedRealTo = 1e7;
constexpr const char* kOtherRealFormat = "%.12E";

// The STEP text of a translated model, written in memory with the formats above.
bool step_text_of(const Handle(StepData_StepModel)& model, std::string& text) {
  const Handle(StepData_Protocol) protocol = Handle(StepData_Protocol)::DownCast(model->Protocol());
  if (protocol.IsNull()) return false;
  StepData_StepWriter writer(model);
  writer.FloatWriter().SetFormat(kOtherRealFormat);  // resets the range and the zero suppression: set after
  writer.FloatWriter().SetFormatForRange(kFixedRealFormat, kFixedRealFrom, kFixedRealTo);
  writer.FloatWriter().SetZeroSuppress(Standard_True);
  writer.SendModel(protocol);
  std::ostringstream out;
  if (!writer.Print(out)) return false;
  text = std::move(out).str();
  return true;
}

// OpenCASCADE's translation of the parts into one assembly, as STEP text; false when the translation fails. The
// document and the writer's model are gone when it returns (a 100,000-beam part's model takes gigabytes).
bool occ_step_text(std::string& text, const std::vector<StepPart>& parts, const std::string& assembly_name,
                   Progress& progress) {
  std::lock_guard<std::mutex> lock(xcaf_mutex());
  Handle(TDocStd_Document) doc = new_document();
  const DocumentCloser closer{doc};
  Handle(XCAFDoc_ShapeTool) shapes = XCAFDoc_DocumentTool::ShapeTool(doc->Main());
  Handle(XCAFDoc_ColorTool) colors = XCAFDoc_DocumentTool::ColorTool(doc->Main());
  const TDF_Label assembly = shapes->NewShape();
  TDataStd_Name::Set(assembly, assembly_name.c_str());
  for (const StepPart& p : parts) {
    // Faces in connected order: readers built on OpenCASCADE then orient each shell in linear time (see there).
    const TDF_Label label = shapes->AddShape(with_faces_in_connected_order(p.shape), Standard_False);
    TDataStd_Name::Set(label, p.name.c_str());
    if (p.has_color)
      colors->SetColor(label, Quantity_Color(p.color[0], p.color[1], p.color[2], Quantity_TOC_RGB), XCAFDoc_ColorGen);
    if (p.instances.empty()) {
      const TDF_Label component = shapes->AddComponent(assembly, label, TopLoc_Location());
      TDataStd_Name::Set(component, p.name.c_str());
    }
    for (std::size_t i = 0; i < p.instances.size(); ++i) {
      const TDF_Label component = shapes->AddComponent(assembly, label, TopLoc_Location(p.instances[i]));
      TDataStd_Name::Set(component, p.name.c_str());
    }
  }
  shapes->UpdateAssemblies();
  progress.advance(5);
  STEPCAFControl_Writer writer;  // its construction initializes the STEP settings: change them after
  writer.SetColorMode(Standard_True);
  writer.SetNameMode(Standard_True);
  // The curves of edges on their faces (pcurves) are written, though they make most of the file: without them
  // (write.surfacecurve.mode 0, a file 4x smaller) OpenCASCADE's reader rebuilds a circle on a sphere as a cubic
  // B-spline 7e-5 away from the circle, 700 times the edge's tolerance, and volumes come back 3e-6 to 6e-6 off
  // (docs/brep.md, section 5). Set here, so that a changed default of the process cannot drop them.
  const ScopedStaticInt with_pcurves("write.surfacecurve.mode", 1);
  {
    Progress part(progress, 45);
    OccProgress occ(part);
    const bool transferred = writer.Transfer(doc, STEPControl_AsIs, nullptr, occ.range());
    // Cancelled when the progress stopped the transfer (it then answers false): a cancel, not a write failure.
    occ.finish();  // also the last chance to stop: the file is written below
    if (!transferred) return false;
  }
  make_reproducible(writer.ChangeWriter().Model());
  return step_text_of(writer.ChangeWriter().Model(), text);
}

}  // namespace

void write_step_assembly(const std::string& path, const std::vector<StepPart>& parts, const std::string& assembly_name,
                         Progress& progress) {
  if (parts.empty()) fail_input("parts", "there is nothing to write");
  check_output_path(path);
  check_step_name(assembly_name, "assembly_name");
  for (const StepPart& p : parts) {
    check_step_name(p.name, "parts");
    if (p.shape.IsNull()) fail_input("parts", "part '" + p.name + "' has no shape");
  }
  // Units: the document 5, the translation to STEP entities 45 (OpenCASCADE reports it), the file 50 (it cannot
  // report: the fraction waits at 0.5 while it is written and its equal geometry shared).
  progress.set_total(100);
  // Written beside the target and renamed (PartialFile), so that a failure or a cancel leaves no file under the
  // name; an unwritable path is refused here, before the translation. OpenCASCADE's text is made in memory and its
  // equal geometry shared (step_shared_geometry.hpp) before anything is written.
  PartialFile file(path);
  std::string text;
  if (!occ_step_text(text, parts, assembly_name, progress))
    fail_input("path", "cannot write a STEP file to '" + path + "'");
  text = share_equal_geometry(std::move(text));
  try {
    file.write(text);
    file.commit();
  } catch (const std::runtime_error& e) {
    fail_input("path", "cannot write a STEP file to '" + path + "' (" + e.what() + ")");
  }
  progress.finish();
}

namespace {

// Reads the file in this process (the reader process's work): the caller holds xcaf_mutex.
std::vector<StepPart> read_step_here(const std::string& path) {
  Handle(TDocStd_Document) doc = new_document();
  STEPCAFControl_Reader reader;
  reader.SetColorMode(Standard_True);
  reader.SetNameMode(Standard_True);
  if (reader.ReadFile(path.c_str()) != IFSelect_RetDone) {
    XCAFApp_Application::GetApplication()->Close(doc);
    fail_input("path", "cannot read '" + path + "' as STEP");
  }
  // Entities whose parameters failed to load (a reference to an entity of the wrong type or none, a malformed
  // value) are kept by the reader with null fields, and its translator dereferences them: a crash, not an error
  // (found by tests/fuzz/fuzz_body_step). Such a file is refused before anything is translated.
  const Handle(Interface_InterfaceModel) model = reader.ChangeReader().WS()->Model();
  const Interface_CheckIterator load_fails = Interface_CheckTool(model).AnalyseCheckList();
  if (!load_fails.IsEmpty(Standard_True) || model->GlobalCheck()->HasFailed()) {
    XCAFApp_Application::GetApplication()->Close(doc);
    std::ostringstream first;
    if (model->GlobalCheck()->HasFailed()) first << model->GlobalCheck()->CFail(1);
    for (load_fails.Start(); load_fails.More(); load_fails.Next())
      if (first.tellp() == 0 && load_fails.Value()->HasFailed()) {
        first << "entity #" << load_fails.Number() << ": " << load_fails.Value()->CFail(1);
        break;
      }
    fail_input("path", "'" + path + "' is not well-formed STEP (" + first.str() + ")");
  }
  reader.Transfer(doc);
  Handle(XCAFDoc_ShapeTool) shapes = XCAFDoc_DocumentTool::ShapeTool(doc->Main());
  Handle(XCAFDoc_ColorTool) colors = XCAFDoc_DocumentTool::ColorTool(doc->Main());
  TDF_LabelSequence roots;
  shapes->GetFreeShapes(roots);
  std::vector<StepPart> out;
  for (int i = 1; i <= roots.Length(); ++i) collect(shapes, colors, roots.Value(i), TopLoc_Location(), "", out);
  XCAFApp_Application::GetApplication()->Close(doc);
  for (const StepPart& part : out) {
    require_complete_geometry(part.shape, "path");
    // The checker, which every caller runs next, has crashed on shapes a reader left incomplete: run it here
    // first, where a crash is an error (sequential: the reader process has no TBB workers).
    BRepCheck_Analyzer(part.shape, Standard_True, Standard_False).IsValid();
  }
  return out;
}

// The parts as the reader process sends them: per part its name, colour and shape (BinTools binary).
void put(std::string& out, const void* data, std::size_t size) { out.append(static_cast<const char*>(data), size); }
void put_string(std::string& out, const std::string& s) {
  const std::uint64_t n = s.size();
  put(out, &n, sizeof n);
  out += s;
}

std::string parts_to_bytes(const std::vector<StepPart>& parts) {
  std::string out;
  const std::uint64_t n = parts.size();
  put(out, &n, sizeof n);
  for (const StepPart& p : parts) {
    put_string(out, p.name);
    const char has_color = p.has_color ? 1 : 0;
    put(out, &has_color, 1);
    put(out, p.color.data(), sizeof p.color);
    put_string(out, shape_to_binary(p.shape));
  }
  return out;
}

// Reads what parts_to_bytes wrote (in the same program, so the same layout).
class PartReader {
 public:
  explicit PartReader(const std::string& bytes) : bytes_(bytes) {}
  void get(void* data, std::size_t size) {
    if (size > bytes_.size() - at_) throw std::runtime_error("the STEP reader process sent a truncated answer");
    std::memcpy(data, bytes_.data() + at_, size);
    at_ += size;
  }
  std::string get_string() {
    std::uint64_t n = 0;
    get(&n, sizeof n);
    if (n > bytes_.size() - at_) throw std::runtime_error("the STEP reader process sent a truncated answer");
    std::string s = bytes_.substr(at_, n);
    at_ += n;
    return s;
  }

 private:
  const std::string& bytes_;
  std::size_t at_ = 0;
};

std::vector<StepPart> parts_from_bytes(const std::string& bytes) {
  PartReader in(bytes);
  std::uint64_t n = 0;
  in.get(&n, sizeof n);
  std::vector<StepPart> parts;
  for (std::uint64_t i = 0; i < n; ++i) {
    StepPart p;
    p.name = in.get_string();
    char has_color = 0;
    in.get(&has_color, 1);
    p.has_color = has_color != 0;
    in.get(p.color.data(), sizeof p.color);
    p.shape = shape_from_binary(in.get_string());
    parts.push_back(std::move(p));
  }
  return parts;
}

}  // namespace

std::vector<StepPart> read_step_parts(const std::string& path) {
  // Held around the fork: the reader process inherits it held by its only thread, and reads without taking it.
  std::lock_guard<std::mutex> lock(xcaf_mutex());
  std::error_code missing;  // a missing file is refused by the reader, with its own message
  const std::uintmax_t size = std::filesystem::file_size(path, missing);
  return parts_from_bytes(run_in_child([&] { return parts_to_bytes(read_step_here(path)); }, "path", "'" + path + "'",
                                       "STEP reader", missing ? 0 : static_cast<std::size_t>(size)));
}

}  // namespace steady
