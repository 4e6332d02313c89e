#include "steady/brep/step_assembly.hpp"

#include <IFSelect_ReturnStatus.hxx>
#include <Quantity_Color.hxx>
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

#include <mutex>

#include "brep/occ_progress.hpp"
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

void write_step_assembly(const std::string& path, const std::vector<StepPart>& parts, const std::string& assembly_name,
                         Progress& progress) {
  if (parts.empty()) fail_input("parts", "there is nothing to write");
  // Units: the document 5, the translation to STEP entities 45 (OpenCASCADE reports it), the file 50 (it cannot
  // report: the fraction waits at 0.5 while it is written).
  progress.set_total(100);
  std::lock_guard<std::mutex> lock(xcaf_mutex());
  Handle(TDocStd_Document) doc = new_document();
  const DocumentCloser closer{doc};
  Handle(XCAFDoc_ShapeTool) shapes = XCAFDoc_DocumentTool::ShapeTool(doc->Main());
  Handle(XCAFDoc_ColorTool) colors = XCAFDoc_DocumentTool::ColorTool(doc->Main());
  const TDF_Label assembly = shapes->NewShape();
  TDataStd_Name::Set(assembly, assembly_name.c_str());
  for (const StepPart& p : parts) {
    if (p.shape.IsNull()) fail_input("parts", "part '" + p.name + "' has no shape");
    const TDF_Label label = shapes->AddShape(p.shape, Standard_False);
    TDataStd_Name::Set(label, p.name.c_str());
    if (p.has_color)
      colors->SetColor(label, Quantity_Color(p.color[0], p.color[1], p.color[2], Quantity_TOC_RGB), XCAFDoc_ColorGen);
    const TDF_Label component = shapes->AddComponent(assembly, label, TopLoc_Location());
    TDataStd_Name::Set(component, p.name.c_str());
  }
  shapes->UpdateAssemblies();
  progress.advance(5);
  STEPCAFControl_Writer writer;
  writer.SetColorMode(Standard_True);
  writer.SetNameMode(Standard_True);
  bool ok = false;
  {
    Progress part(progress, 45);
    OccProgress occ(part);
    ok = writer.Transfer(doc, STEPControl_AsIs, nullptr, occ.range());
    occ.finish();  // the last chance to stop: the file is written below
  }
  ok = ok && writer.Write(path.c_str()) == IFSelect_RetDone;
  if (!ok) fail_input("path", "cannot write a STEP file to '" + path + "'");
  progress.finish();
}

std::vector<StepPart> read_step_parts(const std::string& path) {
  std::lock_guard<std::mutex> lock(xcaf_mutex());
  Handle(TDocStd_Document) doc = new_document();
  STEPCAFControl_Reader reader;
  reader.SetColorMode(Standard_True);
  reader.SetNameMode(Standard_True);
  if (reader.ReadFile(path.c_str()) != IFSelect_RetDone) {
    XCAFApp_Application::GetApplication()->Close(doc);
    fail_input("path", "cannot read '" + path + "' as STEP");
  }
  reader.Transfer(doc);
  Handle(XCAFDoc_ShapeTool) shapes = XCAFDoc_DocumentTool::ShapeTool(doc->Main());
  Handle(XCAFDoc_ColorTool) colors = XCAFDoc_DocumentTool::ColorTool(doc->Main());
  TDF_LabelSequence roots;
  shapes->GetFreeShapes(roots);
  std::vector<StepPart> out;
  for (int i = 1; i <= roots.Length(); ++i) collect(shapes, colors, roots.Value(i), TopLoc_Location(), "", out);
  XCAFApp_Application::GetApplication()->Close(doc);
  return out;
}

}  // namespace steady
