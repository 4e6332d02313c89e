"""Task panels (GUI): editing a document object with live feedback."""
