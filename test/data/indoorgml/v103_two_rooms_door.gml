<?xml version="1.0" encoding="UTF-8"?>
<ns0:IndoorFeatures xmlns:ns0="http://www.opengis.net/indoorgml/1.0/core" xmlns:nv="http://www.opengis.net/indoorgml/1.0/navigation" xmlns:gml="http://www.opengis.net/gml/3.2" xmlns:xlink="http://www.w3.org/1999/xlink" gml:id="IF">
<ns0:primalSpaceFeatures><ns0:PrimalSpaceFeatures gml:id="PS">
<ns0:cellSpaceMember><nv:GeneralSpace gml:id="A"><gml:name>A</gml:name>
<ns0:cellSpaceGeometry><ns0:Geometry3D>
<gml:Solid gml:id="SA"><gml:exterior><gml:Shell>
<gml:surfaceMember><gml:Polygon gml:id="A-floor"><gml:exterior><gml:LinearRing>
<gml:pos>4.0 0.0 0.0</gml:pos>
<gml:pos>4.0 3.0 0.0</gml:pos>
<gml:pos>0.0 3.0 0.0</gml:pos>
<gml:pos>0.0 0.0 0.0</gml:pos>
<gml:pos>4.0 0.0 0.0</gml:pos>
</gml:LinearRing></gml:exterior>
</gml:Polygon>
</gml:surfaceMember>
<gml:surfaceMember><gml:Polygon gml:id="A-ceil"><gml:exterior><gml:LinearRing>
<gml:pos>0.0 3.0 2.5</gml:pos>
<gml:pos>4.0 3.0 2.5</gml:pos>
<gml:pos>4.0 0.0 2.5</gml:pos>
<gml:pos>0.0 0.0 2.5</gml:pos>
<gml:pos>0.0 3.0 2.5</gml:pos>
</gml:LinearRing></gml:exterior>
</gml:Polygon>
</gml:surfaceMember>
<gml:surfaceMember><gml:Polygon gml:id="A-south"><gml:exterior><gml:LinearRing>
<gml:pos>0.0 0.0 2.5</gml:pos>
<gml:pos>4.0 0.0 2.5</gml:pos>
<gml:pos>4.0 0.0 0.0</gml:pos>
<gml:pos>0.0 0.0 0.0</gml:pos>
<gml:pos>0.0 0.0 2.5</gml:pos>
</gml:LinearRing></gml:exterior>
<gml:interior><gml:LinearRing>
<gml:pos>1.0 0.0 1.0</gml:pos>
<gml:pos>1.0 0.0 2.0</gml:pos>
<gml:pos>2.0 0.0 2.0</gml:pos>
<gml:pos>2.0 0.0 1.0</gml:pos>
<gml:pos>1.0 0.0 1.0</gml:pos>
</gml:LinearRing></gml:interior>
</gml:Polygon>
</gml:surfaceMember>
<gml:surfaceMember><gml:Polygon gml:id="A-north"><gml:exterior><gml:LinearRing>
<gml:pos>4.0 3.0 0.0</gml:pos>
<gml:pos>4.0 3.0 2.5</gml:pos>
<gml:pos>0.0 3.0 2.5</gml:pos>
<gml:pos>0.0 3.0 0.0</gml:pos>
<gml:pos>4.0 3.0 0.0</gml:pos>
</gml:LinearRing></gml:exterior>
</gml:Polygon>
</gml:surfaceMember>
<gml:surfaceMember><gml:Polygon gml:id="A-west"><gml:exterior><gml:LinearRing>
<gml:pos>0.0 3.0 0.0</gml:pos>
<gml:pos>0.0 3.0 2.5</gml:pos>
<gml:pos>0.0 0.0 2.5</gml:pos>
<gml:pos>0.0 0.0 0.0</gml:pos>
<gml:pos>0.0 3.0 0.0</gml:pos>
</gml:LinearRing></gml:exterior>
</gml:Polygon>
</gml:surfaceMember>
<gml:surfaceMember><gml:Polygon gml:id="A-east"><gml:exterior><gml:LinearRing>
<gml:pos>4.0 0.0 2.5</gml:pos>
<gml:pos>4.0 3.0 2.5</gml:pos>
<gml:pos>4.0 3.0 0.0</gml:pos>
<gml:pos>4.0 0.0 0.0</gml:pos>
<gml:pos>4.0 0.0 2.5</gml:pos>
</gml:LinearRing></gml:exterior>
</gml:Polygon>
</gml:surfaceMember>
</gml:Shell></gml:exterior></gml:Solid>
</ns0:Geometry3D></ns0:cellSpaceGeometry>
<ns0:duality xlink:href="#SA1"/>
<ns0:partialboundedBy xlink:href="#D1"/>
</nv:GeneralSpace></ns0:cellSpaceMember>
<ns0:cellSpaceMember><nv:GeneralSpace gml:id="B"><gml:name>B</gml:name>
<ns0:cellSpaceGeometry><ns0:Geometry3D>
<gml:Solid gml:id="SB"><gml:exterior><gml:Shell>
<gml:surfaceMember><gml:Polygon gml:id="B-ceil"><gml:exterior><gml:LinearRing>
<gml:pos>4.0 0.0 2.5</gml:pos>
<gml:pos>8.0 0.0 2.5</gml:pos>
<gml:pos>8.0 3.0 2.5</gml:pos>
<gml:pos>4.0 3.0 2.5</gml:pos>
<gml:pos>4.0 0.0 2.5</gml:pos>
</gml:LinearRing></gml:exterior>
</gml:Polygon>
</gml:surfaceMember>
<gml:surfaceMember><gml:Polygon gml:id="B-south"><gml:exterior><gml:LinearRing>
<gml:pos>4.0 0.0 0.0</gml:pos>
<gml:pos>8.0 0.0 0.0</gml:pos>
<gml:pos>8.0 0.0 2.5</gml:pos>
<gml:pos>4.0 0.0 2.5</gml:pos>
<gml:pos>4.0 0.0 0.0</gml:pos>
</gml:LinearRing></gml:exterior>
</gml:Polygon>
</gml:surfaceMember>
<gml:surfaceMember><gml:Polygon gml:id="B-north"><gml:exterior><gml:LinearRing>
<gml:pos>4.0 3.0 0.0</gml:pos>
<gml:pos>4.0 3.0 2.5</gml:pos>
<gml:pos>8.0 3.0 2.5</gml:pos>
<gml:pos>8.0 3.0 0.0</gml:pos>
<gml:pos>4.0 3.0 0.0</gml:pos>
</gml:LinearRing></gml:exterior>
</gml:Polygon>
</gml:surfaceMember>
<gml:surfaceMember><gml:OrientableSurface orientation="-"><gml:baseSurface><gml:Polygon gml:id="B-west"><gml:exterior><gml:LinearRing>
<gml:pos>4.0 3.0 0.0</gml:pos>
<gml:pos>4.0 3.0 2.5</gml:pos>
<gml:pos>4.0 0.0 2.5</gml:pos>
<gml:pos>4.0 0.0 0.0</gml:pos>
<gml:pos>4.0 3.0 0.0</gml:pos>
</gml:LinearRing></gml:exterior>
</gml:Polygon>
</gml:baseSurface></gml:OrientableSurface></gml:surfaceMember>
<gml:surfaceMember><gml:Polygon gml:id="B-east"><gml:exterior><gml:LinearRing>
<gml:pos>8.0 0.0 0.0</gml:pos>
<gml:pos>8.0 3.0 0.0</gml:pos>
<gml:pos>8.0 3.0 2.5</gml:pos>
<gml:pos>8.0 0.0 2.5</gml:pos>
<gml:pos>8.0 0.0 0.0</gml:pos>
</gml:LinearRing></gml:exterior>
</gml:Polygon>
</gml:surfaceMember>
<gml:surfaceMember xlink:href="#B-floor"/>
</gml:Shell></gml:exterior></gml:Solid>
</ns0:Geometry3D></ns0:cellSpaceGeometry>
<ns0:duality xlink:href="#SB1"/>
<ns0:partialboundedBy xlink:href="#D1"/>
</nv:GeneralSpace></ns0:cellSpaceMember>

<ns0:cellSpaceBoundaryMember><ns0:CellSpaceBoundary gml:id="D1"><ns0:duality xlink:href="#T1"/>
<ns0:cellSpaceBoundaryGeometry><ns0:geometry3D><gml:Polygon gml:id="D1-geom"><gml:exterior><gml:LinearRing>
<gml:pos>4.0 1.0 0.0</gml:pos>
<gml:pos>4.0 2.0 0.0</gml:pos>
<gml:pos>4.0 2.0 2.0</gml:pos>
<gml:pos>4.0 1.0 2.0</gml:pos>
<gml:pos>4.0 1.0 0.0</gml:pos>
</gml:LinearRing></gml:exterior>
</gml:Polygon>
</ns0:geometry3D></ns0:cellSpaceBoundaryGeometry></ns0:CellSpaceBoundary></ns0:cellSpaceBoundaryMember>
<ns0:cellSpaceBoundaryMember><ns0:CellSpaceBoundary gml:id="FLOORB"><ns0:cellSpaceBoundaryGeometry><ns0:geometry3D><gml:Polygon gml:id="B-floor"><gml:exterior><gml:LinearRing>
<gml:pos>4.0 0.0 0.0</gml:pos>
<gml:pos>4.0 3.0 0.0</gml:pos>
<gml:pos>8.0 3.0 0.0</gml:pos>
<gml:pos>8.0 0.0 0.0</gml:pos>
<gml:pos>4.0 0.0 0.0</gml:pos>
</gml:LinearRing></gml:exterior>
</gml:Polygon>
</ns0:geometry3D></ns0:cellSpaceBoundaryGeometry></ns0:CellSpaceBoundary></ns0:cellSpaceBoundaryMember>
</ns0:PrimalSpaceFeatures></ns0:primalSpaceFeatures>
<ns0:multiLayeredGraph><ns0:MultiLayeredGraph gml:id="MLG"><ns0:spaceLayers gml:id="SLs"><ns0:spaceLayerMember><ns0:SpaceLayer gml:id="SL">
<ns0:nodes gml:id="N"><ns0:stateMember><ns0:State gml:id="SA1"><ns0:duality xlink:href="#A"/><ns0:geometry><gml:Point gml:id="PA"><gml:pos>1.5 1.5 1.0</gml:pos></gml:Point></ns0:geometry></ns0:State></ns0:stateMember>
<ns0:stateMember><ns0:State gml:id="SB1"><ns0:duality xlink:href="#B"/><ns0:geometry><gml:Point gml:id="PB"><gml:pos>6 1.5 1.0</gml:pos></gml:Point></ns0:geometry></ns0:State></ns0:stateMember></ns0:nodes>
<ns0:edges gml:id="E"><ns0:transitionMember><ns0:Transition gml:id="T1"><ns0:weight>1</ns0:weight><ns0:connects xlink:href="#SA1"/><ns0:connects xlink:href="#SB1"/><ns0:duality xlink:href="#D1"/>
<ns0:geometry><gml:LineString gml:id="LT1"><gml:posList srsDimension="3">1.5 1.5 1 4 1.5 1 6 1.5 1</gml:posList></gml:LineString></ns0:geometry></ns0:Transition></ns0:transitionMember></ns0:edges>
</ns0:SpaceLayer></ns0:spaceLayerMember></ns0:spaceLayers></ns0:MultiLayeredGraph></ns0:multiLayeredGraph>
</ns0:IndoorFeatures>
