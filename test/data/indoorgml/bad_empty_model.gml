<?xml version="1.0" encoding="UTF-8"?>
<IndoorFeatures xmlns="http://www.opengis.net/indoorgml/1.0/core" xmlns:gml="http://www.opengis.net/gml/3.2" xmlns:xlink="http://www.w3.org/1999/xlink" gml:id="EMPTY">
<primalSpaceFeatures><PrimalSpaceFeatures gml:id="PS"/></primalSpaceFeatures>
</IndoorFeatures>
