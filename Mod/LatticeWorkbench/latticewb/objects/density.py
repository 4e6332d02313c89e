"""The Density property the workbench's objects share (g/cm^3), for the mass in the properties report."""


def add_density_property(obj):
    if "Density" not in obj.PropertiesList:
        obj.addProperty("App::PropertyFloat", "Density", "Material",
                        "Density of the material in g/cm^3, for the mass in the properties report (Ti-6Al-4V: 4.43)")
        obj.Density = 1.0
